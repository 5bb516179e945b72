#pragma once
// One row of the transport matrix in the pixel (cubemap texel) basis — the
// bake's hot loop (DESIGN.md §1 "Transport entry"):
//
//   T[s,m] = Ω_m · (1/K) Σ_k V(x + ε n, ω_k) · (1/π) · max(0, n·ω_k)
//
// with the shared jitter pattern's ω_k (albedo factored out). The row depends
// only on (scene, cubemap, pattern, sample, ε): no other randomness.
#include <cstdint>
#include <span>

#include "core/cubemap.h"
#include "core/jitter_pattern.h"
#include "core/ray_caster.h"
#include "core/vec3.h"

namespace wavebake {

// Counters that add up over rows (the job's "rays traced" progress).
struct TransportStats {
  uint64_t rays_traced = 0;    // occlusion rays handed to Embree
  uint64_t rays_occluded = 0;  // of those, blocked
  uint64_t texels_culled = 0;  // texels entirely below the horizon: not traced, exactly 0
};

// position, normal: the sample (normal unit length). epsilon: ray offset along
// the normal (RayCaster::DefaultEpsilon unless the job sets one). row: M =
// cubemap.size() entries, overwritten. pattern must be made for `cubemap`.
// stats may be null. Safe to call concurrently on one RayCaster and pattern.
void TransportRow(const RayCaster& caster, const Cubemap& cubemap, const JitterPattern& pattern,
                  Vec3 position, Vec3 normal, float epsilon, std::span<float> row,
                  TransportStats* stats);
// The same over whatever light domain the pattern was made for (the cube or
// a plane face, core/light_domain.h): row has pattern.texels() entries.
void TransportRow(const RayCaster& caster, const JitterPattern& pattern, Vec3 position, Vec3 normal,
                  float epsilon, std::span<float> row, TransportStats* stats);

}  // namespace wavebake
