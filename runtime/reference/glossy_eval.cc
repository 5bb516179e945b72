#include "runtime/reference/glossy_eval.h"

#include <optional>

#include "core/directions/cubemap.h"
#include "runtime/env/env_resample.h"
#include "runtime/reference/dense_trace.h"

namespace wavebake {

absl::StatusOr<EvalReport> EvaluateGlossy(const std::filesystem::path& store, const EnvMap& env_map,
                                          int terms, const EvalOptions& options) {
  absl::StatusOr<std::unique_ptr<GlossyStore>> opened = GlossyStore::Open(store, options.glossy);
  if (!opened.ok()) return opened.status();
  GlossyStore& g = **opened;
  std::optional<EnvMap> turned;
  if (options.rotate_degrees != 0) turned = Rotated(env_map, options.rotate_degrees);
  const EnvMap& env = turned ? *turned : env_map;
  const StoreInfo& info = g.info();
  absl::StatusOr<RayCaster> caster = BuildBakedScene(info);
  if (!caster.ok()) return caster.status();
  const float eps = BakedEpsilon(info, *caster);

  // The reference sees the same BRDF and views, per sample id.
  const SampleSet& samples = g.samples();
  std::vector<Vec3> sample_views(samples.size());
  for (int cell = 0; cell < samples.cells(); ++cell) {
    if (samples.grid[cell] >= 0) sample_views[samples.grid[cell]] = g.views()[cell];
  }
  ReferenceOptions ref_options = options.reference;
  ref_options.epsilon = eps;
  ref_options.brdf = &g.brdf();
  ref_options.views = sample_views;
  DenseFn dense;
  if (options.dense) {
    dense = [&]() -> absl::StatusOr<DenseTraceResult> {
      const std::vector<float> cube = ResampleToCubemap(env, Cubemap(info.light_res));
      const DenseTraceOptions dense_options{info.light_res, info.params.supersample,
                                            info.params.seed, eps, g.pattern().per_texel};
      return TraceDenseGlossy(*caster, samples, cube, dense_options, g.brdf(), g.views());
    };
  }
  return CompareWithReference(
      *caster, samples, env, ref_options, terms, [&] { return g.RelightImage(env, terms); }, dense);
}

}  // namespace wavebake
