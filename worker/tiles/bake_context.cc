#include "worker/tiles/bake_context.h"

#include "core/bake/bake_gather.h"
#include "core/bake/bake_params_io.h"
#include "core/layouts/sample_layout.h"
#include "core/scene/scene_hash.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake {

absl::StatusOr<std::unique_ptr<BakeContext>> MakeBakeContext(std::string_view scene_spec,
                                                             const BakeParams& params,
                                                             const SceneFiles* files) {
  if (absl::Status s = ValidateBakeParams(params); !s.ok()) return s;
  absl::StatusOr<LayoutSpec> layout = ParseLayout(params.layout);
  if (!layout.ok()) return layout.status();
  SceneReport report;
  absl::StatusOr<Scene> scene = LoadScene(scene_spec, &report, files);
  if (!scene.ok()) return scene.status();
  absl::StatusOr<RayCaster> caster = RayCaster::Build(*scene);
  if (!caster.ok()) return caster.status();

  auto ctx = std::make_unique<BakeContext>(*std::move(caster));
  ctx->scene_spec = std::string(scene_spec);
  ctx->scene = *std::move(scene);
  ctx->scene_report = std::move(report);
  ctx->params = params;
  ctx->layout = *layout;
  ctx->cubemap = Cubemap(params.light_res);
  ctx->scene_hash =
      SceneHash(ctx->scene, layout->kind == LayoutKind::kUv ? layout->uv_channel : -1);
  absl::StatusOr<SampleSet> samples = MakeSampleSet(ctx->scene, ctx->caster, ctx->layout);
  if (!samples.ok()) return samples.status();
  ctx->samples = *std::move(samples);
  if (ctx->samples.size() == 0)
    return absl::InvalidArgumentError("layout: no sample hits the scene (check the camera)");
  absl::StatusOr<JitterPattern> jitter =
      params.light_domain.is_plane()
          ? MakeJitterPattern(PlaneFace(params.light_res, params.light_domain), params.supersample,
                              params.seed)
          : MakeJitterPattern(ctx->cubemap, params.supersample, params.seed);
  if (!jitter.ok()) return jitter.status();
  ctx->jitter = *std::move(jitter);
  if (params.refines()) ctx->refine.emplace(ctx->cubemap, ctx->jitter, RefineOptions{});
  ctx->plan = MakeJobPlan(params, ctx->samples.width, ctx->samples.height);
  ctx->epsilon = params.ray_epsilon > 0 ? params.ray_epsilon : ctx->caster.DefaultEpsilon();
  if (params.bounces != 0) {
    // A few rays per sample (S·R against the direct bake's S·M·K), traced
    // once per context: every task that needs them shares them.
    absl::StatusOr<BakeGathers> gathers =
        MakeBakeGathers(ctx->scene, ctx->caster, ctx->samples, params, *layout, ctx->epsilon);
    if (!gathers.ok()) return gathers.status();
    if (params.bounces == kAutoBounces)
      ctx->auto_bounces = ResolveBounces(params, *gathers, ctx->samples);
    ctx->plan.bounces = ctx->auto_bounces ? ctx->auto_bounces->bounces : params.bounces;
    ctx->plan.aux_samples = gathers->aux.size();
    MarkAuxRows(ctx->plan.bounces, *gathers);
    ctx->bounce = *std::move(gathers);
  }
  return ctx;
}

}  // namespace wavebake
