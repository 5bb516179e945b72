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
  g.aux = VertexSamples(scene, epsilon);
  if (params.bounces != 1) {
    absl::StatusOr<BounceGather> aux = MakeBounceGather(scene, caster, g.aux, options);
    if (!aux.ok()) return aux.status();
    g.aux_gather = *std::move(aux);
  }
  options.stream = 1;  // the pixels' rays: streams apart from the vertices'
  absl::StatusOr<BounceGather> pixels = MakeBounceGather(scene, caster, samples, g.aux, options);
  if (!pixels.ok()) return pixels.status();
  g.gather = *std::move(pixels);
  return g;
}

void MarkAuxRows(int bounces, BakeGathers& g) {
  g.aux_rows.assign(g.uses_aux() ? g.aux.cells() : 0, 0);
  if (!g.uses_aux() || bounces <= 0) return;
  std::vector<int32_t> frontier;
  const auto mark_sources = [&](const BounceGather& op, int row) {
    for (int64_t e = op.offsets[row]; e < op.offsets[row + 1]; ++e) {
      const int32_t j = op.source[e];
      if (!g.aux_rows[j]) {
        g.aux_rows[j] = 1;
        frontier.push_back(j);
      }
    }
  };
  for (int c = 0; c < g.gather.cells; ++c) mark_sources(g.gather, c);
  for (int b = 1; b < bounces && !frontier.empty(); ++b) {
    std::vector<int32_t> rows;
    rows.swap(frontier);
    for (int32_t r : rows) mark_sources(*g.aux_gather, r);
  }
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
