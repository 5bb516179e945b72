#include "driver/eval/reference_measure.h"

#include "absl/strings/str_cat.h"
#include "core/directions/cubemap.h"
#include "driver/relight/staged_relight.h"
#include "runtime/env/env_resample.h"
#include "runtime/reference/dense_trace.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/store_relight.h"
#include "worker/tiles/bake_context.h"

namespace wavebake::driver {

absl::StatusOr<std::unique_ptr<ReferenceMeasure>> ReferenceMeasure::Create(
    const std::string& scene, const BakeParams& params, const std::string& env_spec,
    double target_rel_se) {
  absl::StatusOr<EnvMap> env = LoadEnvMap(env_spec);
  if (!env.ok()) return env.status();
  absl::StatusOr<std::unique_ptr<BakeContext>> ctx = MakeBakeContext(scene, params);
  if (!ctx.ok()) return ctx.status();
  ReferenceOptions options;
  options.target_rel_se = target_rel_se;
  options.epsilon = (*ctx)->epsilon;  // as eval does: the bake's ray offset
  absl::StatusOr<ReferenceResult> reference =
      ComputeReference((*ctx)->caster, (*ctx)->samples, *env, options);
  if (!reference.ok()) return reference.status();
  return std::unique_ptr<ReferenceMeasure>(
      new ReferenceMeasure(*std::move(ctx), *std::move(env), *std::move(reference)));
}

ReferenceMeasure::ReferenceMeasure(std::unique_ptr<BakeContext> ctx, EnvMap env,
                                   ReferenceResult reference)
    : ctx_(std::move(ctx)), env_(std::move(env)), reference_(std::move(reference)) {}

ReferenceMeasure::~ReferenceMeasure() = default;

int ReferenceMeasure::samples() const { return static_cast<int>(ctx_->samples.size()); }

absl::StatusOr<double> ReferenceMeasure::DenseError(int light_res) const {
  const std::vector<float> cube = ResampleToCubemap(env_, Cubemap(light_res));
  const DenseTraceOptions options{light_res, ctx_->params.supersample, ctx_->params.seed,
                                  ctx_->epsilon};
  absl::StatusOr<DenseTraceResult> dense =
      TraceDenseRelight(ctx_->caster, ctx_->samples, cube, options);
  if (!dense.ok()) return dense.status();
  absl::StatusOr<ErrorStats> error =
      CompareFinite(dense->rgb, reference_.rgb, "the dense relighting");
  if (!error.ok()) return error.status();
  return error->rel_rms;
}

absl::StatusOr<double> ReferenceMeasure::StagingError(const BakeContext& trace_ctx,
                                                      const std::filesystem::path& traced) const {
  const std::vector<float> cube = ResampleToCubemap(env_, trace_ctx.cubemap);
  absl::StatusOr<std::vector<float>> rgb = RelightStaging(trace_ctx, traced, cube);
  if (!rgb.ok()) return rgb.status();
  if (rgb->size() != reference_.rgb.size())
    return absl::FailedPreconditionError(
        absl::StrCat("traced: ", traced.string(), " has another sample grid than the reference"));
  absl::StatusOr<ErrorStats> error = CompareFinite(*rgb, reference_.rgb, "the staged relighting");
  if (!error.ok()) return error.status();
  return error->rel_rms;
}

absl::StatusOr<std::vector<double>> ReferenceMeasure::StoreErrors(
    const std::filesystem::path& store, std::span<const int> terms, int* bits) const {
  absl::StatusOr<OpenedStore> opened = OpenStore(store);
  if (!opened.ok()) return opened.status();
  if (bits) *bits = opened->info.bits;
  std::vector<double> errors;
  for (int n : terms) {
    absl::StatusOr<std::vector<float>> rgb = RelightImage(*opened, env_, n);
    if (!rgb.ok()) return rgb.status();
    if (rgb->size() != reference_.rgb.size())
      return absl::FailedPreconditionError(
          absl::StrCat("store: ", store.string(), " has another sample grid than the reference"));
    absl::StatusOr<ErrorStats> error =
        CompareFinite(*rgb, reference_.rgb, "the store's relighting");
    if (!error.ok()) return error.status();
    errors.push_back(error->rel_rms);
  }
  return errors;
}

}  // namespace wavebake::driver
