#pragma once
// Per-sample lighting's view of a store (DESIGN.md §1 "Per-sample
// lighting"): when every sample is lit by its own lighting vector W(x) —
// here a near-field light's coefficients on the sample's face — Eq. 8's
// grouping of shared lights no longer applies, and relighting is, per cell,
//
//   B(x) = Σ_k W_k(x) · T_k(x)
//
// over the terms k chosen for that cell. The matrix is static, so its
// 4D-compressed columns are decoded once, at load: each column image through
// the inverse column transform at its own depth, then transposed into one
// dense row per sampled cell (the row basis, M floats), where a frame's
// terms are gathered by index. Memory: cells × M floats (64 MiB for 128×128
// samples of a plane:S, N = 32 store).
//
// The same decode as SampleRows (runtime/relight/sample_rows.h, DecodeColumnImage),
// kept dense: a near-field frame gathers a few hundred arbitrary terms per
// cell of a one-face M = N² row, where an indexed load beats searching a
// sparse row; the glossy triple product needs the sparse form, since dense
// cube rows (M = 6N²) would be 384 MiB at 128² samples, N = 32.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/columns/compressed_columns.h"
#include "core/layouts/samples.h"

namespace wavebake {

class CellRows {
 public:
  // Checks sizes, depths and positions (errors name the field); the samples
  // must lie on the columns' grid.
  static absl::StatusOr<CellRows> Decode(const CompressedColumns& columns,
                                         const SampleSet& samples);

  int width() const { return width_; }
  int height() const { return height_; }
  int cells() const { return width_ * height_; }
  int columns() const { return columns_; }
  int light_res() const { return light_res_; }
  double seconds() const { return seconds_; }  // of the decode

  // The dense row of `cell` (columns() floats), or null for a masked cell.
  const float* Row(int cell) const {
    return slot_[cell] < 0 ? nullptr : &rows_[size_t(slot_[cell]) * columns_];
  }
  // Σ_j Row(cell)[terms[j]] · rgb[3j..3j+2]; 0 for a masked cell.
  std::array<float, 3> Dot(int cell, std::span<const uint16_t> terms,
                           std::span<const float> rgb) const;

 private:
  int width_ = 0, height_ = 0, columns_ = 0, light_res_ = 0;
  std::vector<int32_t> slot_;  // [cells]: row index or −1
  std::vector<float> rows_;    // [sampled cells × columns]
  double seconds_ = 0;
};

}  // namespace wavebake
