#include "runtime/reference/dense_trace.h"

#include <atomic>
#include <chrono>
#include <limits>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/transport/transport_row.h"
#include "core/util/parallel_for.h"
#include "runtime/glossy/brdf_slices.h"

namespace wavebake {

absl::StatusOr<DenseTraceResult> TraceDenseRelight(const RayCaster& caster,
                                                   const SampleSet& samples,
                                                   std::span<const float> cube_rgb,
                                                   const DenseTraceOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const Cubemap cube(o.light_res);
  if (cube_rgb.size() != 3 * static_cast<size_t>(cube.size())) {
    return absl::InvalidArgumentError(
        absl::StrCat("lighting: ", cube_rgb.size(), " floats for light_res ", o.light_res));
  }
  absl::StatusOr<JitterPattern> jitter = MakeJitterPattern(cube, o.supersample, o.seed);
  if (!jitter.ok()) return jitter.status();
  const float eps = o.epsilon > 0 ? o.epsilon : caster.DefaultEpsilon();
  DenseTraceResult r;
  r.rgb.assign(3 * static_cast<size_t>(samples.cells()), std::numeric_limits<float>::quiet_NaN());
  std::atomic<int64_t> rays{0};
  ParallelFor(samples.cells(), [&](int cell) {
    const int32_t s = samples.grid[cell];
    if (s < 0) return;
    std::vector<float> row(cube.size());
    TransportStats stats;
    TransportRow(caster, cube, *jitter, samples.position[s], samples.normal[s], eps, row, &stats);
    double b[3] = {0, 0, 0};
    for (int m = 0; m < cube.size(); ++m) {
      for (int c = 0; c < 3; ++c) b[c] += double{row[m]} * cube_rgb[3 * m + c];
    }
    const Vec3 a = samples.albedo[s];
    for (int c = 0; c < 3; ++c)
      r.rgb[3 * static_cast<size_t>(cell) + c] = static_cast<float>(b[c] * a[c]);
    rays += static_cast<int64_t>(stats.rays_traced);
  });
  r.rays = rays;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

absl::StatusOr<DenseTraceResult> TraceDenseGlossy(const RayCaster& caster, const SampleSet& samples,
                                                  std::span<const float> cube_rgb,
                                                  const DenseTraceOptions& o, const Brdf& brdf,
                                                  std::span<const Vec3> views) {
  const auto start = std::chrono::steady_clock::now();
  const Cubemap cube(o.light_res);
  if (cube_rgb.size() != 3 * static_cast<size_t>(cube.size())) {
    return absl::InvalidArgumentError(
        absl::StrCat("lighting: ", cube_rgb.size(), " floats for light_res ", o.light_res));
  }
  if (views.size() != static_cast<size_t>(samples.cells()))
    return absl::InvalidArgumentError(
        absl::StrCat("views: ", views.size(), " for ", samples.cells(), " grid cells"));
  absl::StatusOr<JitterPattern> jitter = MakeJitterPattern(cube, o.supersample, o.seed);
  if (!jitter.ok()) return jitter.status();
  absl::StatusOr<JitterPattern> rho_jitter =
      MakeJitterPattern(cube, o.brdf_supersample > 0 ? o.brdf_supersample : o.supersample, o.seed);
  if (!rho_jitter.ok()) return rho_jitter.status();
  const BrdfTexels texels(&*rho_jitter);
  const float eps = o.epsilon > 0 ? o.epsilon : caster.DefaultEpsilon();
  DenseTraceResult r;
  r.rgb.assign(3 * static_cast<size_t>(samples.cells()), std::numeric_limits<float>::quiet_NaN());
  std::atomic<int64_t> rays{0};
  ParallelFor(samples.cells(), [&](int cell) {
    const int32_t s = samples.grid[cell];
    if (s < 0) return;
    std::vector<float> v(cube.size()), rho(cube.size(), 0.0f);
    TransportStats stats;
    VisibilityRow(caster, cube, *jitter, samples.position[s], samples.normal[s], eps, v, &stats);
    texels.Evaluate(brdf, samples.normal[s], views[cell], 0, rho);
    double b[3] = {0, 0, 0};
    for (int m = 0; m < cube.size(); ++m) {
      const double vr = double{v[m]} * rho[m];
      for (int c = 0; c < 3; ++c) b[c] += vr * cube_rgb[3 * m + c];
    }
    const Vec3 a = samples.albedo[s];
    for (int c = 0; c < 3; ++c)
      r.rgb[3 * static_cast<size_t>(cell) + c] = static_cast<float>(b[c] * a[c]);
    rays += static_cast<int64_t>(stats.rays_traced);
  });
  r.rays = rays;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace wavebake
