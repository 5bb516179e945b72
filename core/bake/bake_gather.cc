#include "core/bake/bake_gather.h"

#include "core/layouts/vertex_samples.h"

namespace wavebake {

bool UsesAuxSamples(const BakeParams& params, const LayoutSpec& layout) {
  return params.bounces != 0 && layout.kind == LayoutKind::kCamera;
}

int AuxSampleCount(const Scene& scene, const BakeParams& params, const LayoutSpec& layout) {
  return UsesAuxSamples(params, layout) ? static_cast<int>(VertexCount(scene)) : 0;
}

absl::StatusOr<BakeGathers> MakeBakeGathers(const Scene& scene, const RayCaster& caster,
                                            const SampleSet& samples, const BakeParams& params,
                                            const LayoutSpec& layout, float epsilon) {
  BounceGatherOptions options{
      .rays = params.gather_rays,
      .seed = params.seed,
      .epsilon = epsilon,
      .uv_channel = layout.kind == LayoutKind::kUv ? layout.uv_channel : -1};
  BakeGathers g;
  if (!UsesAuxSamples(params, layout)) {
    absl::StatusOr<BounceGather> gather = MakeBounceGather(scene, caster, samples, options);
    if (!gather.ok()) return gather.status();
    g.gather = *std::move(gather);
    return g;
  }
  g.aux = VertexSamples(scene);
  absl::StatusOr<BounceGather> aux = MakeBounceGather(scene, caster, g.aux, options);
  if (!aux.ok()) return aux.status();
  g.aux_gather = *std::move(aux);
  options.stream = 1;  // the pixels' rays: streams apart from the vertices'
  absl::StatusOr<BounceGather> pixels = MakeBounceGather(scene, caster, samples, g.aux, options);
  if (!pixels.ok()) return pixels.status();
  g.gather = *std::move(pixels);
  return g;
}

AutoBounceChoice ResolveBounces(const BakeParams& params, const BakeGathers& gathers,
                                const SampleSet& samples) {
  if (params.bounces != kAutoBounces) {
    AutoBounceChoice fixed;
    fixed.bounces = params.bounces;
    return fixed;
  }
  const double target = params.column_terms > 0 ? 0.0 : params.target_error;
  if (gathers.aux_gather)
    return AutoBounces(*gathers.aux_gather, gathers.aux.grid, target, kMaxBounces);
  return AutoBounces(gathers.gather, samples.grid, target, kMaxBounces);
}

}  // namespace wavebake
