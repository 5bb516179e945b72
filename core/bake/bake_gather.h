#pragma once
// The gather operators of a bake (core/transport/bounce_gather.h) as its
// parameters define them: the one construction shared by every worker's
// bake context, the coordinator's plan and `eval`'s uncompressed answer, so
// all of them hold the same operators.
//
// Mesh and lightmap layouts gather from their own samples: T = Σ_b G^b T₀.
// A camera layout's pixels see only some surfaces, so its bounces gather
// from an auxiliary set, every vertex of the meshes (core/layouts/
// vertex_samples.h), whose direct rows A₀ are baked beside the pixels':
//   T = T₀ + G_ca Σ_{b<B} G_aa^b A₀
// with G_ca the pixels' gather from the auxiliary set and G_aa the set's
// gather from itself (Sloan et al. 2002 §5 gathers over mesh vertices too).
// The set's boundary vertices sit ε inside their meshes (VertexSamples'
// inset: a vertex where one mesh meets another would read as black).
#include <cstdint>
#include <optional>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "core/layouts/layout.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"
#include "core/transport/bounce_gather.h"
#include "core/transport/ray_caster.h"

namespace wavebake {

// Whether a bake's bounces need the auxiliary set: bounces on a camera layout.
bool UsesAuxSamples(const BakeParams& params, const LayoutSpec& layout);
// Its size (0 when not used), known to a planner from the scene alone.
int AuxSampleCount(const Scene& scene, const BakeParams& params, const LayoutSpec& layout);

struct BakeGathers {
  BounceGather gather;  // rows over the layout's cells
  // UsesAuxSamples: `gather` reads the auxiliary set (G_ca), `aux_gather` is
  // G_aa over `aux`, built only when a bounce gathers the set's own bounced
  // light (B ≥ 2, or auto): one bounce is G_ca A₀ alone.
  std::optional<BounceGather> aux_gather;
  SampleSet aux;
  // Per auxiliary sample: whether B bounces read its direct row (MarkAuxRows);
  // the rows of the others are never traced and stay zero.
  std::vector<uint8_t> aux_rows;
  bool uses_aux() const { return aux.size() > 0; }
};

// The operators for `samples` (the layout's, from MakeSampleSet) with
// params.gather_rays directions per sample, seeded by params.seed; epsilon:
// the bake's ray offset. Errors: a layout whose samples carry no vertex ids or
// lightmap texels and is no camera (named "bounces").
absl::StatusOr<BakeGathers> MakeBakeGathers(const Scene& scene, const RayCaster& caster,
                                            const SampleSet& samples, const BakeParams& params,
                                            const LayoutSpec& layout, float epsilon);

// The auxiliary samples whose direct rows B bounces of the camera read,
// into g.aux_rows: G_ca Σ_{b<B} G_aa^b A₀ reads the sources of G_ca, then
// the sources of G_aa's rows of those, B − 1 times. A vertex that no pixel's
// gather reaches in B hops (the back of a wall, the underside of a floor)
// adds nothing, so tracing its row would be wasted. Needs g.aux_gather when
// bounces ≥ 2.
void MarkAuxRows(int bounces, BakeGathers& g);

// The bounce count a bake with `params` adds: params.bounces, or for auto
// AutoBounces' choice (on the auxiliary set's G_aa when there is one) for the
// target error, or for a fixed term count the most.
AutoBounceChoice ResolveBounces(const BakeParams& params, const BakeGathers& gathers,
                                const SampleSet& samples);

}  // namespace wavebake
