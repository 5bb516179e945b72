#pragma once
// One row of T by visibility refinement: trace only where visibility changes
// (DESIGN.md §1 "Transport entry", computed by refinement).
//
// Brute force (core/transport/transport_row.h) traces the K jittered rays of every
// texel above the horizon, N² work per face, while what the row holds —
// where visibility changes — lies along occluder silhouettes, N long. Here
// every cube face is a quadtree of texel blocks (core/transport/refine_plan.h):
//
//  1. One ray probes each start block (the jittered ray 0 of its anchor texel).
//  2. A block whose probe agrees with the probes (or decided values) of its 8
//     neighbours is uniform: every texel in it gets its value without rays.
//     Any other block is split in 4 and its children probed, down to single
//     texels. Blocks entirely below the horizon are 0 and dropped; one the
//     horizon crosses is refined like any other, its probe permitting (a
//     probe below the horizon says nothing: that block is split).
//  3. A texel still undecided there traces its K jittered rays (ray 0 was
//     its probe).
//  4. Silhouette following (RefineOptions::follow): a traced texel whose rays
//     disagree has its decided neighbours traced; one whose rays agree but
//     whose neighbour was decided the other way has that neighbour traced;
//     repeated until nothing changes.
//
// Values (V the visibility, c_k = n·ω_k, I_m = (1/π)∫_m max(0, n·ω) dω the
// exact integral of core/directions/texel_irradiance.h: n·Φ_m for a texel entirely
// above the horizon, the clipped polygon's integral for one it crosses):
//   * a decided occluded texel, or one below the horizon: 0;
//   * a decided visible texel: I_m;
//   * a traced texel: I_m · Σ V_k c_k / Σ c_k over its rays above the
//     horizon, the cosine-weighted visible fraction of its rays times the
//     exact integral — so a fully visible texel is I_m whether it was traced
//     or decided, and blocks meet without seams in the row's Haar
//     coefficients; 0 if none of its rays is above the horizon (a sliver no
//     ray samples, as brute force).
// With nothing occluding, the row sums to 1 up to float rounding and those
// slivers (brute force: up to the quadrature error of the horizon band and
// elsewhere). The result depends only on (scene, cubemap, pattern, plan,
// sample, ε): deterministic, like brute force.
#include <cstdint>
#include <span>
#include <vector>

#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/transport/ray_caster.h"
#include "core/transport/refine_plan.h"
#include "core/transport/transport_row.h"
#include "core/util/vec3.h"

namespace wavebake {

// A texel being traced: its rays' sums, in k order.
struct RefineSlot {
  int32_t texel;
  bool above;  // entirely above the horizon
  int rays_above = 0, visible = 0;
  float sum_c = 0, sum_vc = 0;
};

// Per-thread working memory of a row, reused row after row (O(M) bytes).
struct RefineScratch {
  std::vector<uint8_t> state;  // per texel, refined_row.cc's TexelState
  std::vector<int8_t> probe;   // per texel: its ray 0, -1 untraced, -2 below the horizon
  std::vector<int8_t> vote;    // per texel: refined_row.cc's RowRefiner::vote_
  std::vector<int32_t> active, next, to_trace, frontier;
  std::vector<uint8_t> crossing;  // per active block: the horizon crosses it
  std::vector<RefineSlot> slots;
};

// As TransportRow, by refinement; plan and pattern must be made for
// `cubemap`. stats->rays_traced counts the rays handed to Embree.
void RefinedTransportRow(const RayCaster& caster, const Cubemap& cubemap,
                         const JitterPattern& pattern, const RefinePlan& plan, Vec3 position,
                         Vec3 normal, float epsilon, std::span<float> row, TransportStats* stats,
                         RefineScratch& scratch);

}  // namespace wavebake
