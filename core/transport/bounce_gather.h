#pragma once
// One diffuse bounce of light transport as a linear operator on the sample
// grid (Sloan et al. 2002 §5, Ng et al. 2003 §3; the interreflection that the
// two-factor transport T = V·ρ of vollick-lessig-haar-triple-product.md Eq. 9–10
// can hold and the triple product's Eq. 16 cannot):
//
//   T_b(x, ·) = 1/π ∫ ρ̄(y) T_{b−1}(y, ·) max(0, n·ω') dω',   y = first hit from x along ω'
//
// with ρ(x) factored out of T as for T_0 (DESIGN.md §1: the sample's albedo
// is applied at relight time) and the albedo of the surface that reflects,
// ρ̄(y), inside T_b. The store holds one scalar T per sample, so ρ̄ is the
// mean of y's RGB albedo: exact for grey surfaces, and colour bleeding (a red
// wall tinting its neighbour) is not represented.
//
// T_{b−1}(y) is interpolated from the samples: barycentrically over the hit
// triangle's vertices for the vertex layouts (hilbert, grid), bilinearly over
// the lightmap texels around y's texture coordinate for the uv layouts (the
// covered ones; surfaces without samples — the other meshes of a grid
// layout — reflect nothing). The integral is
// estimated with R cosine-distributed, stratified directions per sample
// (seeded by the job seed and the sample id, so the operator — and every
// store built with it — is the same on any number of workers and threads):
//
//   T_b[c] = Σ_j G[c, j] T_{b−1}[j],  G[c, j] = (1/R) Σ_rays ρ̄(y_r) β_j(y_r)
//
// (the cosine and 1/π cancel against the cosine density). G acts on the
// spatial index only, so it commutes with the row transform: it applies to
// Haar-domain rows, or column by column to the staged column images, as is.
// Rays that escape add nothing (the environment is T_0's), rays that reach
// the back of a surface add nothing (a sample's row is its front side's).
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"
#include "core/transport/ray_caster.h"

namespace wavebake {

struct BounceGatherOptions {
  int rays = 64;        // R per sample, rounded up to a square (q×q strata)
  uint64_t seed = 1;    // the job seed
  float epsilon = 0;    // ray offset along the normal; 0: caster.DefaultEpsilon()
  int threads = 0;      // 0: all cores (the operator does not depend on it)
  int uv_channel = -1;  // a uv layout's UV channel; −1: a vertex layout
  // Keeps the random streams of operators over other receivers apart (the
  // camera's gather into its auxiliary set, core/bake/bake_gather.h).
  uint64_t stream = 0;
};

// G over the W×H cells, compressed sparse rows: row c (a cell) has entries
// [offsets[c], offsets[c+1]) of `source` (cells, ascending, distinct) and
// `weight`. Masked cells have empty rows and are never a source.
struct BounceGather {
  int cells = 0;    // receivers: the rows
  int sources = 0;  // the cells `source` indexes (= cells when square)
  int rays = 0;     // R actually traced per sample (the square)
  std::vector<int64_t> offsets;
  std::vector<int32_t> source;
  std::vector<float> weight;
  uint64_t hits = 0;  // rays that reached a front face (statistics)

  // out[c] = Σ_j G[c, j] in[j], summed in float in entry order (deterministic).
  // in has `sources` entries, out `cells`; they must not overlap.
  void Apply(std::span<const float> in, std::span<float> out) const;
  // Apply to n ≤ kMaxBlock vectors at once, interleaved: in[j·n + k] is
  // element j of vector k, out[c·n + k] likewise. Each output is summed as
  // Apply sums it (the same bits); one pass over the entries serves n
  // vectors, their n values contiguous. 64 (eight 8-float registers of sums)
  // measured faster than 32 and 16 on cubes-wall's camera (camera 128²,
  // N = 32, one bounce: the product's phase 2.48 s of CPU against 2.59 and
  // 3.89 s), though fewer of a bigger block's sources are all zero.
  static constexpr int kMaxBlock = 64;
  void ApplyBlock(std::span<const float> in, std::span<float> out, int n) const;
  int64_t entries() const { return static_cast<int64_t>(source.size()); }
};

// Builds G for a vertex layout (samples.vertex maps sample → global vertex id
// of `scene`, the scene `caster` was built from) or, with options.uv_channel,
// a uv layout (samples.uv_charts, one per mesh). A sample set of neither kind
// (the camera layout) is InvalidArgument naming "bounces".
absl::StatusOr<BounceGather> MakeBounceGather(const Scene& scene, const RayCaster& caster,
                                              const SampleSet& samples,
                                              const BounceGatherOptions& options);
// The same with rows over another set's cells: the gather rays start at the
// `receivers` (any sample set on the surfaces: a camera's pixels), the
// previous bounce is interpolated from `samples` as above. cells =
// receivers.cells(), sources = samples.cells().
absl::StatusOr<BounceGather> MakeBounceGather(const Scene& scene, const RayCaster& caster,
                                              const SampleSet& receivers, const SampleSet& samples,
                                              const BounceGatherOptions& options);

// What `--bounces auto` resolves to: the smallest B such that bounce B+1
// would add less than half of target_error (the share of the budget the
// bounces left out may take; the column selection has the rest) in relative
// RMS over the samples, estimated on the operator alone by power iteration
// from T_0·1 ≈ 1 (every sample fully lit, an upper bound of the direct light
// under uniform lighting, so the bounces' relative size is not
// underestimated): estimate[b] = ‖G^b 1‖ / ‖1‖ over the samples of `grid`.
// At most kMaxBounces (core/bake/bake_params.h); target_error 0 gives the most.
struct AutoBounceChoice {
  int bounces = 0;
  std::vector<double> estimate;  // [0..bounces+1] (estimate[0] = 1)
};
AutoBounceChoice AutoBounces(const BounceGather& gather, std::span<const int32_t> grid,
                             double target_error, int max_bounces);

}  // namespace wavebake
