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

#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/transport/ray_caster.h"
#include "core/util/vec3.h"

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
// a plane face, core/directions/light_domain.h): row has pattern.texels() entries,
// traced in index order (the cube's overload above traces in Z order, which
// is faster, and gives the same row).
void TransportRow(const RayCaster& caster, const JitterPattern& pattern, Vec3 position, Vec3 normal,
                  float epsilon, std::span<float> row, TransportStats* stats);

// The visibility row of DESIGN.md §1 "What a row holds" (`visibility`):
//
//   V[s,m] = (1/K) Σ_k v(x + ε n, ω_k),  v = 1 if the ray escapes, 0 if it hits,
//
// no solid angle, no cosine, no BRDF (they are the triple product's other
// factor, runtime/glossy/glossy_relighter.h). Directions below the sample's tangent
// plane (n·ω_k ≤ 0) are not traced and count as visible: every integrand
// that uses V carries the BRDF's max(0, n·ω) factor, which is 0 there, and
// leaving V = 1 spares the row the hard horizon edge a traced "0 below"
// would put into every row's Haar expansion (an unoccluded sample is then
// V ≡ 1: six scaling coefficients).
void VisibilityRow(const RayCaster& caster, const Cubemap& cubemap, const JitterPattern& pattern,
                   Vec3 position, Vec3 normal, float epsilon, std::span<float> row,
                   TransportStats* stats);

// The rays TransportRow traces for a sample of this normal, counted without
// tracing them (the same horizon culling and per-ray test): brute force's
// cost, for comparing refinement against it at resolutions where brute
// force itself would take long.
uint64_t BruteForceRays(const Cubemap& cubemap, const JitterPattern& pattern, Vec3 normal);

}  // namespace wavebake
