#pragma once
// The transport matrix of a store decoded into memory for relighting
// (DESIGN.md §1 "Relighting"): CSC by light column, values dequantized and
// unscaled but still in each column's own transform domain (depth[m] steps
// of column_filter over the W×H sample grid, Mallat layout).
#include <cstdint>
#include <vector>

#include "core/bake/bake_params.h"

namespace wavebake {

struct CompressedColumns {
  int width = 0, height = 0;  // sample grid
  int light_res = 0;          // N; columns = 6 N²
  int columns = 0;
  WaveletFilter row_filter = WaveletFilter::kHaar;
  WaveletFilter column_filter = WaveletFilter::kHaar;
  std::vector<int64_t> indptr;    // [columns + 1]
  std::vector<uint32_t> indices;  // [nnz] position y*W + x
  std::vector<float> values;      // [nnz]
  std::vector<uint8_t> depth;     // [columns]
};

}  // namespace wavebake
