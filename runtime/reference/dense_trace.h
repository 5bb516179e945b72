#pragma once
// The uncompressed answer of `eval` (DESIGN.md §5 "dense"): B = T·L with T
// retraced row by row exactly as the bake traced it — the same cubemap, the
// same shared jitter pattern (job seed, K), the same ray offset and the same
// row kernel (core/transport/transport_row.h) — and L the lighting resampled onto that
// cubemap in the pixel basis (no row transform, no approximation). So the
// dense error against the reference is the discretization error of T itself,
// and compressed − dense is what compression and the n-term lighting cost.
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/products/brdf.h"
#include "core/transport/ray_caster.h"

namespace wavebake {

struct DenseTraceOptions {
  int light_res = 32;   // N of the store
  int supersample = 4;  // K of the store
  uint64_t seed = 1;    // job seed of the store (jitter pattern)
  float epsilon = 0;    // ray offset; 0: caster.DefaultEpsilon() as in the bake
  // Glossy only: directions per texel of the BRDF factor's quadrature
  // (runtime/glossy/brdf_slices.h); 0 = supersample.
  int brdf_supersample = 0;
};

struct DenseTraceResult {
  std::vector<float> rgb;  // [cells*3], × albedo, NaN where masked
  int64_t rays = 0;
  double seconds = 0;
};

// cube_rgb: [3 * 6N²] texel mean radiance (ResampleToCubemap). Runs on all
// cores; the result does not depend on their number.
absl::StatusOr<DenseTraceResult> TraceDenseRelight(const RayCaster& caster,
                                                   const SampleSet& samples,
                                                   std::span<const float> cube_rgb,
                                                   const DenseTraceOptions& options);

// The uncompressed answer for a glossy material on a visibility store: every
// row V(x) retraced as the bake traced it (core/transport/transport_row.h
// VisibilityRow), the BRDF factor texel by texel (runtime/glossy/brdf_slices.h
// BrdfTexels, the store's jitter directions) and B(x) = albedo · Σ_m L_m V_m
// ρ_m in the pixel basis: no Haar basis, no tripling coefficient, no
// approximation of any factor. views: per grid cell, towards the eye.
absl::StatusOr<DenseTraceResult> TraceDenseGlossy(const RayCaster& caster, const SampleSet& samples,
                                                  std::span<const float> cube_rgb,
                                                  const DenseTraceOptions& options,
                                                  const Brdf& brdf, std::span<const Vec3> views);

}  // namespace wavebake
