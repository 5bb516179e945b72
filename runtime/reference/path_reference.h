#pragma once
// The independent ground truth of `eval --reference` for stores with diffuse
// bounces: a Monte-Carlo path tracer that estimates, per sample,
//
//   B(x) = ρ(x) Σ_{b=0..B} L_b(x),
//   L_0(x) = ∫ V(x, ω) L(ω) max(0, n·ω)/π dω,
//   L_b(x) = ∫ ρ̄(y) L_{b−1}(y) max(0, n·ω)/π dω   (y the first hit along ω)
//
// — the quantity a B-bounce store holds (core/transport/bounce_gather.h: ρ(x) is the
// sample's RGB albedo, ρ̄(y) the mean of the hit surface's RGB albedo, back
// faces black), but computed the path tracer's way: each path starts at x,
// at every vertex takes one next-event estimate of the environment
// (importance-sampled from the lat-long map, runtime/env/env_sampler.h: at x the
// receiver's cosine-bounded block distribution, at later vertices the map's
// own), then continues along one cosine-distributed direction to the first
// hit, its throughput multiplied by ρ̄(y) (cosine and 1/π cancel against the
// density), for at most B bounces. The environment is reached only through
// the next-event estimates (a continued ray that escapes ends the path), so
// every path length counts it exactly once.
//
// Nothing of the baked transport enters: no cubemap, no jitter pattern, no
// Haar basis, no sample interpolation (y's normal is the hit's own
// interpolated normal), and its own random stream and direction sampling;
// rays are traced through the path tracer's own Embree scene
// (runtime/reference/path_scene.h), not the bake's ray caster.
//
// Paths come in batches of 64 (the first uniform of each next-event draw at
// x stratified over the batch); the standard error is that of the batch
// means. Stopping rule as runtime/reference/reference.h: a pilot of min_paths per
// sample, then each sample until its SE_c·ρ_c ≤ target_rel_se·RMS(B) or
// max_paths. Deterministic: each sample has its own stream seeded by (seed,
// sample id), bit-identical for any number of threads.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/reference.h"

namespace wavebake {

struct PathReferenceOptions {
  int bounces =
      1;  // B ≥ 0 (0: direct light only, the same quantity as runtime/reference/reference.h)
  double target_rel_se = 0.002;
  uint64_t seed = 1;
  int threads = 0;              // 0: all cores
  int min_paths = 1024;         // per sample, the pilot
  int64_t max_paths = 1 << 20;  // per sample
  float epsilon = 0;            // ray offset along n; 0: PathScene::Offset()
  // As ReferenceOptions::progress (runtime/reference/reference.h): sample
  // visits done of 2 · samples, from the tracing threads.
  std::function<void(int64_t done, int64_t total)> progress = nullptr;
};

// scene: its meshes and albedos (checked by CheckAndRepairScene). env must be
// lat-long. The result is as ComputeReference's (rays: every ray traced).
absl::StatusOr<ReferenceResult> ComputePathReference(const Scene& scene, const SampleSet& samples,
                                                     const EnvMap& env,
                                                     const PathReferenceOptions& options = {});

}  // namespace wavebake
