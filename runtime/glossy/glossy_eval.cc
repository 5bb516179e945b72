#include "runtime/glossy/glossy_eval.h"

#include <chrono>

#include "core/directions/cubemap.h"
#include "runtime/env/env_resample.h"
#include "runtime/reference/dense_trace.h"

namespace wavebake {
namespace {

double GlossySecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

absl::StatusOr<EvalReport> EvaluateGlossy(const std::filesystem::path& store,
                                          std::string_view env_spec, int terms,
                                          const EvalOptions& options) {
  absl::StatusOr<std::unique_ptr<GlossyStore>> opened = GlossyStore::Open(store, options.glossy);
  if (!opened.ok()) return opened.status();
  GlossyStore& g = **opened;
  absl::StatusOr<EnvMap> env = LoadEnvMap(env_spec);
  if (!env.ok()) return env.status();
  if (options.rotate_degrees != 0) *env = Rotated(*env, options.rotate_degrees);
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
  EvalReport report;
  report.terms = terms;
  ReferenceOptions ref_options = options.reference;
  ref_options.epsilon = eps;
  ref_options.brdf = &g.brdf();
  ref_options.views = sample_views;
  absl::StatusOr<ReferenceResult> reference = ComputeReference(*caster, samples, *env, ref_options);
  if (!reference.ok()) return reference.status();
  report.reference_rel_se = reference->rel_se;
  report.reference_rays = reference->rays;
  report.reference_seconds = reference->seconds;
  report.reference_converged = reference->converged;

  auto t0 = std::chrono::steady_clock::now();
  absl::StatusOr<std::vector<float>> compressed = g.RelightImage(*env, terms);
  if (!compressed.ok()) return compressed.status();
  const double compressed_seconds = GlossySecondsSince(t0);
  report.compressed = CompareToReference(*compressed, reference->rgb);
  report.compressed.seconds = compressed_seconds;

  if (options.dense) {
    t0 = std::chrono::steady_clock::now();
    const std::vector<float> cube = ResampleToCubemap(*env, Cubemap(info.light_res));
    const DenseTraceOptions dense_options{info.light_res, info.params.supersample, info.params.seed,
                                          eps, g.pattern().per_texel};
    absl::StatusOr<DenseTraceResult> dense =
        TraceDenseGlossy(*caster, samples, cube, dense_options, g.brdf(), g.views());
    if (!dense.ok()) return dense.status();
    report.dense = CompareToReference(dense->rgb, reference->rgb);
    report.dense.seconds = GlossySecondsSince(t0);
    report.has_dense = true;
    report.dense_rays = dense->rays;
  }
  return report;
}

}  // namespace wavebake
