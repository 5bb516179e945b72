#include "runtime/glossy/brdf_slices.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>

#include "absl/strings/str_cat.h"
#include "core/directions/cubemap.h"
#include "core/util/parallel_for.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

bool BelowHorizon(const JitterPattern& p, int m, Vec3 n) {
  const Vec3* c = &p.corners[static_cast<size_t>(m) * 4];
  return Dot(n, c[0]) <= 0 && Dot(n, c[1]) <= 0 && Dot(n, c[2]) <= 0 && Dot(n, c[3]) <= 0;
}

}  // namespace

BrdfTexels::BrdfTexels(const JitterPattern* pattern) : pattern_(pattern) {
  const int m_count = pattern->texels();
  centre_.resize(m_count);
  cos_r_.resize(m_count);
  sin_r_.resize(m_count);
  radius_.resize(m_count);
  for (int m = 0; m < m_count; ++m) {
    const Vec3* c = &pattern->corners[static_cast<size_t>(m) * 4];
    const Vec3 centre = Normalize(c[0] + c[1] + c[2] + c[3]);
    float cos_r = 1;
    for (int k = 0; k < 4; ++k) cos_r = std::min(cos_r, Dot(centre, c[k]));
    cos_r = std::max(-1.0f, cos_r - 1e-6f);  // a hair wider against rounding
    centre_[m] = centre;
    cos_r_[m] = cos_r;
    sin_r_[m] = std::sqrt(std::max(0.0f, 1 - cos_r * cos_r));
    radius_[m] = std::acos(cos_r);
  }
}

std::array<bool, 6> BrdfTexels::Evaluate(const Brdf& brdf, Vec3 n, Vec3 wo, double cutoff,
                                         std::span<float> cube) const {
  const JitterPattern& p = *pattern_;
  const LobeCone cone = brdf.Support(n, wo, cutoff);
  const bool whole = cone.cos_angle <= -1;
  const float cos_c = std::clamp(cone.cos_angle, -1.0f, 1.0f);
  const float sin_c = std::sqrt(std::max(0.0f, 1 - cos_c * cos_c));
  const float theta_c = std::acos(cos_c);
  const int per_face = p.n * p.n;
  const double inv_k = 1.0 / p.per_texel;
  std::array<bool, 6> touched{};
  for (int m = 0; m < p.texels(); ++m) {
    if (!whole && theta_c + radius_[m] < 3.14159f) {
      // Outside the cone iff angle(centre, axis) > θ_cone + r.
      if (Dot(centre_[m], cone.axis) < cos_c * cos_r_[m] - sin_c * sin_r_[m]) continue;
    }
    if (BelowHorizon(p, m, n)) continue;
    const size_t first = static_cast<size_t>(m) * p.per_texel;
    const double sum =
        brdf.SumOverDirections(n, wo, &p.x[first], &p.y[first], &p.z[first], p.per_texel);
    if (sum == 0) continue;
    cube[m] = static_cast<float>(p.solid_angle[m] * sum * inv_k);
    touched[m / per_face] = true;
  }
  return touched;
}

std::array<bool, 6> BrdfTexels::Slice(const Brdf& brdf, Vec3 n, Vec3 wo, double cutoff,
                                      std::span<float> cube) const {
  const std::array<bool, 6> touched = Evaluate(brdf, n, wo, cutoff, cube);
  const int nn = pattern_->n, per_face = nn * nn, depth = MaxDepth(nn, nn);
  for (int face = 0; face < 6; ++face) {
    if (touched[face])
      Forward2d(WaveletFilter::kHaar, cube.subspan(face * per_face, per_face), nn, nn, depth);
  }
  return touched;
}

void KeepLargest(std::span<const uint32_t> index, std::span<const float> value, int n,
                 std::vector<uint32_t>& out_index, std::vector<float>& out_value) {
  if (n <= 0 || index.size() <= static_cast<size_t>(n)) {
    out_index.insert(out_index.end(), index.begin(), index.end());
    out_value.insert(out_value.end(), value.begin(), value.end());
    return;
  }
  // Linear-time selection by (|value| down, index up), then index order.
  thread_local std::vector<std::pair<float, uint32_t>> order;
  order.clear();
  for (size_t i = 0; i < index.size(); ++i) order.push_back({std::fabs(value[i]), uint32_t(i)});
  const auto first = [&](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  };
  std::nth_element(order.begin(), order.begin() + n, order.end(), first);
  std::sort(order.begin(), order.begin() + n,
            [](const auto& a, const auto& b) { return a.second < b.second; });
  for (int k = 0; k < n; ++k) {
    out_index.push_back(index[order[k].second]);
    out_value.push_back(value[order[k].second]);
  }
}

BrdfSlices CutSlices(const BrdfSlices& full, int n) {
  BrdfSlices out;
  out.light_res = full.light_res;
  const int cells = static_cast<int>(full.first.size()) - 1;
  out.first.assign(cells + 1, 0);
  for (int c = 0; c < cells; ++c) {
    KeepLargest(full.Index(c), full.Value(c), n, out.index, out.value);
    out.first[c + 1] = static_cast<int64_t>(out.index.size());
  }
  return out;
}

absl::StatusOr<JitterPattern> BrdfQuadrature(int light_res, int store_supersample, uint64_t seed,
                                             const SliceOptions& options) {
  if (options.quadrature < 0 || options.quadrature > 256)
    return absl::InvalidArgumentError(absl::StrCat("brdf quadrature: ", options.quadrature,
                                                   " directions per texel is not in 0..256"));
  return MakeJitterPattern(Cubemap(light_res),
                           options.quadrature > 0 ? options.quadrature : store_supersample, seed);
}

absl::StatusOr<BrdfSlices> ProjectBrdfSlices(const Brdf& brdf, const SampleSet& samples,
                                             std::span<const Vec3> views,
                                             const JitterPattern& pattern,
                                             const SliceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int cells = samples.cells();
  if (views.size() != static_cast<size_t>(cells) || samples.grid.size() != views.size())
    return absl::InvalidArgumentError(
        absl::StrCat("views: ", views.size(), " directions for ", cells, " grid cells"));
  if (options.terms < 0)
    return absl::InvalidArgumentError(absl::StrCat("brdf terms: ", options.terms, " < 0"));
  const BrdfTexels texels(&pattern);
  const int per_face = pattern.n * pattern.n;
  std::vector<std::vector<uint32_t>> index(cells);
  std::vector<std::vector<float>> value(cells);
  ParallelFor(cells, [&](int cell) {
    const int32_t s = samples.grid[cell];
    if (s < 0) return;
    thread_local std::vector<float> cube, candidates;
    thread_local std::vector<uint32_t> where;
    cube.assign(pattern.texels(), 0.0f);
    const std::array<bool, 6> touched =
        texels.Slice(brdf, samples.normal[s], views[cell], options.lobe_cutoff, cube);
    candidates.clear();
    where.clear();
    for (int face = 0; face < 6; ++face) {
      if (!touched[face]) continue;
      for (int m = face * per_face; m < (face + 1) * per_face; ++m) {
        if (cube[m] == 0) continue;
        candidates.push_back(cube[m]);
        where.push_back(static_cast<uint32_t>(m));
      }
    }
    KeepLargest(where, candidates, options.terms, index[cell], value[cell]);
  });

  BrdfSlices out;
  out.light_res = pattern.n;
  out.first.assign(cells + 1, 0);
  for (int c = 0; c < cells; ++c) out.first[c + 1] = out.first[c] + index[c].size();
  out.index.reserve(out.first.back());
  out.value.reserve(out.first.back());
  for (int c = 0; c < cells; ++c) {
    out.index.insert(out.index.end(), index[c].begin(), index[c].end());
    out.value.insert(out.value.end(), value[c].begin(), value[c].end());
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace wavebake
