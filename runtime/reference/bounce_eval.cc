#include "runtime/reference/bounce_eval.h"

#include <cmath>
#include <limits>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/bake/bake_gather.h"
#include "core/directions/cubemap.h"
#include "core/layouts/sample_layout.h"
#include "runtime/env/env_resample.h"
#include "runtime/reference/path_reference.h"

namespace wavebake {
namespace {

// The bounces added to a [cells*3] irradiance image `rgb` (NaN in masked
// cells, which no operator reads), channel by channel: Σ_{b=1..B} G^b E over
// the layout's own samples, or with an auxiliary set (core/bake/bake_gather.h)
// Σ_{b=1..B} G_ca G_aa^{b−1} E_a from its irradiance `aux_rgb`.
void AddBouncesToImage(const BakeGathers& gathers, int bounces, std::span<const float> aux_rgb,
                       std::vector<float>& rgb) {
  const bool aux = gathers.uses_aux();
  const std::span<const float> start = aux ? aux_rgb : std::span<const float>(rgb);
  const size_t cells = rgb.size() / 3, sources = start.size() / 3;
  std::vector<float> previous(sources), next(sources), bounce(cells);
  for (int c = 0; c < 3; ++c) {
    for (size_t i = 0; i < sources; ++i)
      previous[i] = std::isnan(start[3 * i + c]) ? 0.0f : start[3 * i + c];
    std::vector<float> sum(cells, 0.0f);
    for (int b = 1; b <= bounces; ++b) {
      gathers.gather.Apply(previous, bounce);
      for (size_t i = 0; i < cells; ++i) sum[i] += bounce[i];
      if (aux) {
        if (b == bounces) break;  // G_aa is built only when a bounce reads it
        gathers.aux_gather->Apply(previous, next);
        previous.swap(next);
      } else {
        previous.swap(bounce);  // sources = cells
      }
    }
    for (size_t i = 0; i < cells; ++i)
      if (!std::isnan(rgb[3 * i + c])) rgb[3 * i + c] += sum[i];
  }
}

void TimesAlbedo(const SampleSet& samples, std::vector<float>& rgb) {
  for (size_t cell = 0; cell < samples.grid.size(); ++cell) {
    const int32_t s = samples.grid[cell];
    if (s < 0) continue;
    for (int c = 0; c < 3; ++c) rgb[3 * cell + c] *= samples.albedo[s][c];
  }
}

}  // namespace

int StoreBounces(const StoreInfo& info) {
  if (info.params.bounces != kAutoBounces) return info.params.bounces;
  return info.attrs.value(nlohmann::json::json_pointer("/bounces/count"), 0);
}

absl::StatusOr<EvalReport> EvaluateBounces(OpenedStore& opened, const EnvMap& env, int terms,
                                           const EvalOptions& options) {
  if (options.bounces > kMaxBounces)
    return absl::InvalidArgumentError(
        absl::StrCat("bounces: ", options.bounces, " is outside 0..", kMaxBounces));
  const StoreInfo& info = opened.info;
  absl::StatusOr<Scene> scene = LoadBakedScene(info);
  if (!scene.ok()) return scene.status();
  absl::StatusOr<RayCaster> caster = RayCaster::Build(*scene);
  if (!caster.ok()) return caster.status();
  const float eps = BakedEpsilon(info, *caster);
  const int store_bounces = StoreBounces(info);
  const int bounces = options.bounces >= 0 ? options.bounces : store_bounces;

  ReferenceOptions ref_options = options.reference;
  ref_options.epsilon = eps;
  absl::StatusOr<ReferenceResult> reference =
      bounces == 0 ? ComputeReference(*caster, opened.samples, env, ref_options)
                   : ComputePathReference(*scene, opened.samples, env,
                                          {.bounces = bounces,
                                           .target_rel_se = ref_options.target_rel_se,
                                           .seed = ref_options.seed,
                                           .threads = ref_options.threads,
                                           .epsilon = eps,
                                           .progress = ref_options.progress});
  if (!reference.ok()) return reference.status();

  // Dense T₀ relit without the samples' albedo (G reads the irradiance the
  // hit points reflect), then the bounces, then the albedo.
  std::vector<float> direct;
  DenseFn dense;
  if (options.dense) {
    dense = [&]() -> absl::StatusOr<DenseTraceResult> {
      const std::vector<float> cube = ResampleToCubemap(env, Cubemap(info.light_res));
      const DenseTraceOptions trace{info.light_res, info.params.supersample, info.params.seed, eps};
      SampleSet white = opened.samples;
      for (Vec3& a : white.albedo) a = {1, 1, 1};
      absl::StatusOr<DenseTraceResult> traced = TraceDenseRelight(*caster, white, cube, trace);
      if (!traced.ok()) return traced.status();
      if (store_bounces > 0) {
        absl::StatusOr<LayoutSpec> layout = ParseLayout(info.params.layout);
        if (!layout.ok()) return layout.status();
        absl::StatusOr<SampleSet> samples = MakeSampleSet(*scene, *caster, *layout);
        if (!samples.ok()) return samples.status();
        if (samples->grid != opened.samples.grid)
          return absl::FailedPreconditionError(
              "layout: the scene's samples no longer match the store's grid");
        absl::StatusOr<BakeGathers> gathers =
            MakeBakeGathers(*scene, *caster, *samples, info.params, *layout, eps);
        if (!gathers.ok()) return gathers.status();
        std::vector<float> aux_rgb;
        if (gathers->uses_aux()) {  // the auxiliary set's direct light, as the bake traced it
          SampleSet aux = gathers->aux;
          for (Vec3& albedo : aux.albedo) albedo = {1, 1, 1};
          absl::StatusOr<DenseTraceResult> a = TraceDenseRelight(*caster, aux, cube, trace);
          if (!a.ok()) return a.status();
          traced->rays += a->rays;
          aux_rgb = std::move(a->rgb);
        }
        direct = traced->rgb;
        TimesAlbedo(opened.samples, direct);
        AddBouncesToImage(*gathers, store_bounces, aux_rgb, traced->rgb);
      }
      TimesAlbedo(opened.samples, traced->rgb);
      return traced;
    };
  }
  absl::StatusOr<EvalReport> report = CompareWithReference(
      *reference, terms, [&] { return RelightImage(opened, env, terms); }, dense);
  if (!report.ok()) return report.status();
  report->bounces = bounces;
  report->store_bounces = store_bounces;
  if (!direct.empty()) {
    absl::StatusOr<ErrorStats> e = CompareFinite(direct, reference->rgb, "the direct light");
    if (!e.ok()) return e.status();
    report->direct = *e;
    report->has_direct = true;
  }
  return report;
}

}  // namespace wavebake
