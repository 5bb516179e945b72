#pragma once
// The independent ground truth of `eval --reference --area-light`: per
// sample, a Monte-Carlo estimate over the lights' areas of
//
//   B(x) = albedo · (1/π) Σ_lights ∫_A L(y) V(x, y) cos θ_x cos θ_y / |y − x|² dA
//
// with θ_x against the sample's normal, θ_y against the light's normal (−axis:
// it emits towards the side of the plane below it, runtime/near_field/area_light.h), L the
// light's texture read where the point falls, and V from Embree over the
// scene. Never through a face, a canvas, wavelets or T: it shares only the
// light's description (area_light.h) with the wavelet path.
//
// Each batch puts strata² stratified, jittered points on every light; batch
// means are independent, so their spread gives the standard error. Every
// sample has its own random stream seeded by (seed, sample id): the result
// is bit-identical for any number of threads.
//
// It also measures what an expanded face of size S misses (§5.4.3): a
// direction from x to y passes through the face iff
// 2·max(|d·s_axis|, |d·t_axis|) / (d·major) ≤ S, so each draw's contribution
// is split by the smallest S that would have caught it.
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/directions/cubemap.h"
#include "core/layouts/samples.h"
#include "core/transport/ray_caster.h"
#include "runtime/near_field/area_light.h"

namespace wavebake {

struct AreaReferenceOptions {
  int axis = kPosY;  // the light plane's normal (the store's light domain)
  int strata = 16;   // per batch and light: strata² points
  int batches = 8;   // per sample
  uint64_t seed = 1;
  int threads = 0;    // 0: all cores
  float epsilon = 0;  // ray offset along n; 0: caster.DefaultEpsilon()
  std::vector<double> face_sizes = {2, 3, 4, 5, 6, 8, 10};  // S for grazing_loss
};

struct AreaReferenceResult {
  std::vector<float> rgb;             // [cells*3], × albedo, NaN in masked cells
  std::vector<float> standard_error;  // [cells*3]
  double rel_se = 0;                  // sqrt(Σ SE²) / sqrt(Σ B²)
  // Per face_sizes[j]: Σ over samples and channels of the part of B from
  // directions outside a face of that size, over Σ B.
  std::vector<double> grazing_loss;
  int64_t rays = 0;
  double seconds = 0;
};

// Errors name the bad option (strata, batches, axis).
absl::StatusOr<AreaReferenceResult> ComputeAreaReference(const RayCaster& caster,
                                                         const SampleSet& samples,
                                                         std::span<const AreaLight> lights,
                                                         const AreaReferenceOptions& options);

}  // namespace wavebake
