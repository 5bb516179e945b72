#include "runtime/relight/sample_rows.h"

#include <chrono>
#include <cmath>
#include <utility>

#include "core/util/parallel_for.h"
#include "core/wavelets/wavelet2d.h"
#include "runtime/relight/relighter.h"

namespace wavebake {
void DecodeColumnImage(const CompressedColumns& t, int m, std::span<float> image) {
  std::fill(image.begin(), image.end(), 0.0f);
  for (int64_t k = t.indptr[m]; k < t.indptr[m + 1]; ++k) image[t.indices[k]] = t.values[k];
  Inverse2d(t.column_filter, image, t.width, t.height, t.depth[m]);
}

namespace {

// Column m's image, its cells with |value| > drop_below as (cell, value).
void DecodeColumnEntries(const CompressedColumns& t, int m, float drop_below,
                         std::vector<float>& image, std::vector<std::pair<uint32_t, float>>& out) {
  DecodeColumnImage(t, m, image);
  out.clear();
  for (size_t cell = 0; cell < image.size(); ++cell) {
    if (std::fabs(image[cell]) > drop_below)
      out.push_back({static_cast<uint32_t>(cell), image[cell]});
  }
}

}  // namespace

absl::StatusOr<SampleRows> SampleRows::Decode(const CompressedColumns& t, float drop_below) {
  const auto start = std::chrono::steady_clock::now();
  if (absl::Status s = CheckColumns(t); !s.ok()) return s;
  const size_t cells = static_cast<size_t>(t.width) * t.height;
  const int per_face = t.light_res * t.light_res;
  std::vector<std::vector<std::pair<uint32_t, float>>> images(t.columns);
  ParallelFor(t.columns, [&](int m) {
    thread_local std::vector<float> image;
    image.resize(cells);
    DecodeColumnEntries(t, m, drop_below, image, images[m]);
  });

  SampleRows r;
  r.width_ = t.width;
  r.height_ = t.height;
  r.light_res_ = t.light_res;
  // Counting sort of the entries by (cell, face); within a segment the
  // columns arrive in increasing order.
  r.first_.assign(cells * 6 + 1, 0);
  for (int m = 0; m < t.columns; ++m) {
    const int face = m / per_face;
    for (const auto& [cell, v] : images[m]) ++r.first_[cell * 6 + face + 1];
  }
  for (size_t i = 1; i < r.first_.size(); ++i) r.first_[i] += r.first_[i - 1];
  const int64_t nnz = r.first_.back();
  r.terms_.resize(nnz);
  r.values_.resize(nnz);
  std::vector<int64_t> next(r.first_.begin(), r.first_.end() - 1);
  for (int m = 0; m < t.columns; ++m) {
    const int face = m / per_face;
    for (const auto& [cell, v] : images[m]) {
      const int64_t k = next[cell * 6 + face]++;
      r.terms_[k] = static_cast<uint32_t>(m);
      r.values_[k] = v;
    }
    std::vector<std::pair<uint32_t, float>>().swap(images[m]);
  }
  r.stats_.nonzeros = nnz;
  r.stats_.bytes = nnz * (sizeof(uint32_t) + sizeof(float)) + r.first_.size() * sizeof(int64_t);
  r.stats_.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::span<const uint32_t> SampleRows::terms(int cell, int face) const {
  const int64_t b = first_[cell * 6 + face], e = first_[cell * 6 + face + 1];
  return {terms_.data() + b, static_cast<size_t>(e - b)};
}

std::span<const float> SampleRows::values(int cell, int face) const {
  const int64_t b = first_[cell * 6 + face], e = first_[cell * 6 + face + 1];
  return {values_.data() + b, static_cast<size_t>(e - b)};
}

std::array<float, 3> SampleRows::Dot(int cell, const RgbCube& w) const {
  float r = 0, g = 0, b = 0;
  const float* rgb = w.rgb.data();
  for (int face = 0; face < 6; ++face) {
    if (!w.touched[face]) continue;
    const int64_t end = first_[cell * 6 + face + 1];
    for (int64_t k = first_[cell * 6 + face]; k < end; ++k) {
      const float* wj = rgb + 3 * static_cast<size_t>(terms_[k]);
      const float v = values_[k];
      r += v * wj[0];
      g += v * wj[1];
      b += v * wj[2];
    }
  }
  return {r, g, b};
}

}  // namespace wavebake
