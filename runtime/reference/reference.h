#pragma once
// The independent ground truth of `wavebake eval --reference` (DESIGN.md §5):
// per sample, a Monte-Carlo estimate of
//
//   B(x) = albedo · ∫ V(x + ε n, ω) L(ω) max(0, n·ω) / π dω
//
// against the lat-long environment itself (the piecewise-constant function
// EnvRadiance reads), never through the cubemap or T. Visibility comes from
// Embree (core/transport/ray_caster.h) over the scene rebuilt from the store's scene
// spec. Directions are importance-sampled from the map (runtime/env/env_sampler.h:
// Y·Ω per pixel, blocks weighted by a cosine bound per receiver), so tiny,
// very bright sources (grace.hdr) are found.
//
// Draws come in batches of 128 whose first uniform (the block-curve CDF of
// the sampler) is stratified, one jittered stratum per draw: a batch covers
// the receiver's light evenly instead of by chance, which cuts the variance
// several-fold on broad skies. Each batch mean is an independent unbiased
// estimate; the standard error is that of the batch means.
//
// Stopping rule: the reference's own error in the metric eval reports,
// rel_se = sqrt(Σ SE²) / sqrt(Σ B²) over all samples and channels, must be
// below target_rel_se (0.2 %). Every sample first gets min_rays (at least 8
// batches: a pilot that estimates R = RMS of B); then each sample continues
// batch by batch until SE_c ≤ target · R for each channel c, or max_rays.
// Since every sample ends with SE ≤ target·R, the aggregate meets the target
// (unless max_rays stops a sample first; `converged` says).
//
// Deterministic: each sample has its own random stream seeded by (seed,
// sample id) and fixed batch and check points, so the result is bit-identical
// for any number of threads.
//
// Glossy materials (options.brdf, not Lambert): B(x) = albedo · ∫ V L f_r
// max(0, n·ω) dω with f_r evaluated for the sample's view (options.views).
// Half of every batch is drawn from the environment as above — with each
// block weighted by a bound of f_r·cos over it (Brdf::CapBound) instead of
// the cosine alone, so the draws go where the lobe looks — half from
// the BRDF's lobe (Brdf::Sample), and each draw is weighted by the balance
// heuristic f / (½ p_env + ½ p_brdf) (Veach 1997, the multi-sample
// estimator with equal counts): the tiny bright sources of grace.hdr are
// found by the first, narrow highlights by the second. Both halves are
// stratified in their first uniform. Nothing here touches the cubemap, the
// Haar basis or the store's rows.
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/products/brdf.h"
#include "core/transport/ray_caster.h"
#include "runtime/env/env_map.h"

namespace wavebake {

struct ReferenceOptions {
  double target_rel_se = 0.002;
  uint64_t seed = 1;
  int threads = 0;             // 0: std::thread::hardware_concurrency()
  int min_rays = 1024;         // per sample, the pilot
  int64_t max_rays = 1 << 22;  // per sample
  float epsilon = 0;           // ray offset along n; 0: caster.DefaultEpsilon()
  // Glossy reference: borrowed BRDF (null or lambert: the diffuse estimator
  // above) and, per sample id, the unit direction towards the viewer.
  const Brdf* brdf = nullptr;
  std::span<const Vec3> views;
};

struct ReferenceResult {
  std::vector<float> rgb;             // [cells*3], × albedo, NaN in masked cells
  std::vector<float> standard_error;  // [cells*3], × albedo, NaN in masked cells
  double rel_se = 0;                  // sqrt(Σ SE²) / sqrt(Σ B²)
  int64_t rays = 0;                   // occlusion rays traced, all samples
  bool converged = true;              // no sample stopped at max_rays
  double seconds = 0;
};

// env must be lat-long (width = 2·height); errors name the bad field.
absl::StatusOr<ReferenceResult> ComputeReference(const RayCaster& caster, const SampleSet& samples,
                                                 const EnvMap& env,
                                                 const ReferenceOptions& options = {});

}  // namespace wavebake
