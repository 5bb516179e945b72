#include "runtime/relight/cell_rows.h"

#include <chrono>

#include "core/util/parallel_for.h"
#include "runtime/relight/relighter.h"
#include "runtime/relight/sample_rows.h"

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
  // Columns write disjoint entries of rows_: any thread count gives the same rows.
  ParallelFor(r.columns_, [&](int c) {
    if (columns.indptr[c] == columns.indptr[c + 1]) return;  // an empty column is 0 everywhere
    thread_local std::vector<float> image;
    image.resize(r.cells());
    DecodeColumnImage(columns, c, image);
    for (int cell = 0; cell < r.cells(); ++cell)
      if (r.slot_[cell] >= 0) r.rows_[size_t(r.slot_[cell]) * r.columns_ + c] = image[cell];
  });
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
