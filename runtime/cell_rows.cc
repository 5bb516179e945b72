#include "runtime/cell_rows.h"

#include <chrono>

#include "core/wavelet2d.h"
#include "runtime/relighter.h"

namespace wavebake {

absl::StatusOr<CellRows> CellRows::Decode(const CompressedColumns& columns,
                                          const SampleSet& samples) {
  if (absl::Status s = CheckRelightable(columns, samples); !s.ok()) return s;
  const auto t0 = std::chrono::steady_clock::now();
  CellRows r;
  r.width_ = columns.width;
  r.height_ = columns.height;
  r.columns_ = columns.columns;
  r.light_res_ = columns.light_res;
  r.slot_.assign(r.cells(), -1);
  int32_t sampled = 0;
  for (int cell = 0; cell < r.cells(); ++cell)
    if (samples.grid[cell] >= 0) r.slot_[cell] = sampled++;
  r.rows_.assign(size_t(sampled) * r.columns_, 0.0f);
  std::vector<float> image(r.cells());
  for (int c = 0; c < r.columns_; ++c) {
    const int64_t b = columns.indptr[c], e = columns.indptr[c + 1];
    if (b == e) continue;  // an empty column is 0 everywhere
    std::fill(image.begin(), image.end(), 0.0f);
    for (int64_t k = b; k < e; ++k) image[columns.indices[k]] = columns.values[k];
    Inverse2d(columns.column_filter, image, r.width_, r.height_, columns.depth[c]);
    for (int cell = 0; cell < r.cells(); ++cell)
      if (r.slot_[cell] >= 0) r.rows_[size_t(r.slot_[cell]) * r.columns_ + c] = image[cell];
  }
  r.seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::array<float, 3> CellRows::Dot(int cell, std::span<const uint16_t> terms,
                                   std::span<const float> rgb) const {
  const float* row = Row(cell);
  std::array<float, 3> sum{};
  if (!row) return sum;
  for (size_t j = 0; j < terms.size(); ++j) {
    const float t = row[terms[j]];
    sum[0] += t * rgb[3 * j];
    sum[1] += t * rgb[3 * j + 1];
    sum[2] += t * rgb[3 * j + 2];
  }
  return sum;
}

}  // namespace wavebake
