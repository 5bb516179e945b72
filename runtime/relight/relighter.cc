#include "runtime/relight/relighter.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/util/check_or_die.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {

absl::Status CheckColumns(const CompressedColumns& t) {
  const int64_t cells = int64_t{t.width} * t.height;
  if (t.width <= 0 || t.height <= 0 || (t.width & (t.width - 1)) || (t.height & (t.height - 1))) {
    return absl::InvalidArgumentError(
        absl::StrCat("transport: grid ", t.width, "x", t.height, " is not a power-of-two size"));
  }
  const int face = t.light_res * t.light_res;  // a plane light domain has one face
  if (t.light_res <= 0 || (t.columns != 6 * face && t.columns != face)) {
    return absl::InvalidArgumentError(absl::StrCat("transport: columns ", t.columns,
                                                   " != 6 N² or N² for light_res ", t.light_res));
  }
  if (t.indptr.size() != static_cast<size_t>(t.columns) + 1 || t.indptr.front() != 0) {
    return absl::InvalidArgumentError(absl::StrCat("transport/indptr: ", t.indptr.size(),
                                                   " entries for ", t.columns, " columns"));
  }
  if (t.depth.size() != static_cast<size_t>(t.columns)) {
    return absl::InvalidArgumentError(
        absl::StrCat("transport/depth: ", t.depth.size(), " entries for ", t.columns, " columns"));
  }
  if (t.indices.size() != t.values.size() ||
      t.indptr.back() != static_cast<int64_t>(t.indices.size())) {
    return absl::InvalidArgumentError(absl::StrCat("transport: indptr ends at ", t.indptr.back(),
                                                   " but there are ", t.indices.size(),
                                                   " indices and ", t.values.size(), " values"));
  }
  const int max_depth = MaxDepth(t.width, t.height);
  for (int m = 0; m < t.columns; ++m) {
    if (t.indptr[m + 1] < t.indptr[m]) {
      return absl::InvalidArgumentError(absl::StrCat("transport/indptr: decreases at column ", m));
    }
    if (t.depth[m] > max_depth) {
      return absl::InvalidArgumentError(absl::StrCat("transport/depth: column ", m, " has depth ",
                                                     int{t.depth[m]}, " > ", max_depth));
    }
  }
  for (size_t k = 0; k < t.indices.size(); ++k) {
    if (t.indices[k] >= cells) {
      return absl::InvalidArgumentError(absl::StrCat("transport/indices: entry ", k, " = ",
                                                     t.indices[k], " is outside the ", t.width, "x",
                                                     t.height, " grid"));
    }
  }
  return absl::OkStatus();
}

namespace {

absl::Status CheckSamples(const SampleSet& s, const CompressedColumns& t) {
  if (s.width != t.width || s.height != t.height) {
    return absl::InvalidArgumentError(absl::StrCat("samples: grid ", s.width, "x", s.height,
                                                   " differs from the transport's ", t.width, "x",
                                                   t.height));
  }
  if (s.grid.size() != static_cast<size_t>(s.cells()) || s.albedo.size() != s.position.size()) {
    return absl::InvalidArgumentError(absl::StrCat("samples: grid has ", s.grid.size(),
                                                   " cells, albedo ", s.albedo.size(),
                                                   " entries for ", s.size(), " samples"));
  }
  for (int32_t id : s.grid) {
    if (id < -1 || id >= s.size()) {
      return absl::InvalidArgumentError(
          absl::StrCat("samples/grid: sample id ", id, " outside [-1, ", s.size(), ")"));
    }
  }
  return absl::OkStatus();
}

}  // namespace

std::vector<float> CellAlbedo(const SampleSet& samples) {
  std::vector<float> out(static_cast<size_t>(samples.cells()) * 3,
                         std::numeric_limits<float>::quiet_NaN());
  for (size_t cell = 0; cell < samples.grid.size(); ++cell) {
    const int32_t id = samples.grid[cell];
    if (id < 0) continue;
    const Vec3 a = samples.albedo[id];
    out[3 * cell] = a.x;
    out[3 * cell + 1] = a.y;
    out[3 * cell + 2] = a.z;
  }
  return out;
}

absl::Status CheckRelightable(const CompressedColumns& columns, const SampleSet& samples) {
  if (absl::Status s = CheckColumns(columns); !s.ok()) return s;
  return CheckSamples(samples, columns);
}

absl::StatusOr<Relighter> Relighter::Create(const CompressedColumns& columns,
                                            const SampleSet& samples) {
  if (absl::Status s = CheckRelightable(columns, samples); !s.ok()) return s;
  if (MaxDepth(columns.width, columns.height) >= kDepthSlots) {
    return absl::InvalidArgumentError(absl::StrCat("transport: grid ", columns.width, "x",
                                                   columns.height, " is too large to relight"));
  }
  Relighter r;
  r.width_ = columns.width;
  r.height_ = columns.height;
  r.light_res_ = columns.light_res;
  r.row_filter_ = columns.row_filter;
  r.column_filter_ = columns.column_filter;
  r.first_ = columns.indptr;
  r.depth_ = columns.depth;
  r.entries_.resize(columns.indices.size());
  for (size_t k = 0; k < columns.indices.size(); ++k) {
    r.entries_[k] = {columns.indices[k], columns.values[k]};
  }
  r.albedo_ = CellAlbedo(samples);
  r.planes_.assign(static_cast<size_t>(r.cells()) * 3, 0.0f);
  return r;
}

int Relighter::SortByDepth(std::span<const WaveletLight> lights) {
  group_count_.fill(0);
  const uint32_t columns = static_cast<uint32_t>(depth_.size());
  for (const WaveletLight& l : lights) {
    CheckOrDie("Relighter", l.column < columns, "light column out of range for this matrix");
    ++group_count_[depth_[l.column]];
  }
  int deepest = -1;
  uint32_t start = 0;
  for (int d = kDepthSlots - 1; d >= 0; --d) {
    group_start_[d] = start;
    start += group_count_[d];
    if (deepest < 0 && group_count_[d] > 0) deepest = d;
  }
  order_.resize(lights.size());  // no allocation once grown
  std::array<uint32_t, kDepthSlots> next = group_start_;
  for (const WaveletLight& l : lights) order_[next[depth_[l.column]]++] = &l;
  return deepest;
}

void Relighter::AddColumn(const WaveletLight& light) {
  const size_t n = static_cast<size_t>(cells());
  float* r = planes_.data();
  float* g = r + n;
  float* b = g + n;
  const float wr = light.weight[0], wg = light.weight[1], wb = light.weight[2];
  const Entry* e = entries_.data() + first_[light.column];
  const Entry* end = entries_.data() + first_[light.column + 1];
  for (; e != end; ++e) {
    const uint32_t p = e->position;
    const float v = e->value;
    r[p] += wr * v;
    g[p] += wg * v;
    b[p] += wb * v;
  }
}

void Relighter::Accumulate(std::span<const WaveletLight> lights) {
  std::fill(planes_.begin(), planes_.end(), 0.0f);
  const int deepest = SortByDepth(lights);
  const size_t n = static_cast<size_t>(cells());
  for (int d = deepest; d >= 0; --d) {
    // Eq. 8: the group of columns transformed to depth d joins the buffer,
    // which then holds B at depth d; one single step S'_{d→d−1} follows.
    const uint32_t first = group_start_[d], last = first + group_count_[d];
    for (uint32_t k = first; k < last; ++k) AddColumn(*order_[k]);
    if (d == 0) break;
    for (int c = 0; c < 3; ++c) {
      InverseStep(column_filter_, std::span<float>(planes_.data() + c * n, n), width_, height_,
                  d - 1);
    }
  }
}

void Relighter::RelightTransport(std::span<const WaveletLight> lights, std::span<float> rgb_out) {
  CheckOrDie("Relighter", rgb_out.size() == planes_.size(), "output is not W*H*3 floats");
  Accumulate(lights);
  const size_t n = static_cast<size_t>(cells());
  const float* r = planes_.data();
  for (size_t i = 0; i < n; ++i) {
    rgb_out[3 * i] = r[i];
    rgb_out[3 * i + 1] = r[n + i];
    rgb_out[3 * i + 2] = r[2 * n + i];
  }
}

void Relighter::Relight(const WaveletLights& lights, std::span<float> rgb_out) {
  CheckOrDie("Relighter", lights.light_res == light_res_,
             "lights were made for another light resolution");
  CheckOrDie("Relighter", rgb_out.size() == planes_.size(), "output is not W*H*3 floats");
  Accumulate(lights.lights);
  const size_t n = static_cast<size_t>(cells());
  const float* r = planes_.data();
  const float* a = albedo_.data();
  for (size_t i = 0; i < n; ++i) {
    rgb_out[3 * i] = r[i] * a[3 * i];
    rgb_out[3 * i + 1] = r[n + i] * a[3 * i + 1];
    rgb_out[3 * i + 2] = r[2 * n + i] * a[3 * i + 2];
  }
}

void Relighter::ApplyAlbedo(std::span<const float> transport_rgb, std::span<float> rgb_out) const {
  CheckOrDie("Relighter",
             transport_rgb.size() == albedo_.size() && rgb_out.size() == albedo_.size(),
             "ApplyAlbedo: buffers are not W*H*3 floats");
  for (size_t i = 0; i < albedo_.size(); ++i) rgb_out[i] = transport_rgb[i] * albedo_[i];
}

}  // namespace wavebake
