#include "runtime/eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/cubemap.h"
#include "core/scene_hash.h"
#include "runtime/dense_trace.h"
#include "runtime/env_resample.h"
#include "runtime/glossy_eval.h"
#include "runtime/path_reference.h"
#include "runtime/store_relight.h"
#include "storage/scene_loader.h"

namespace wavebake {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::json StatsJson(const ErrorStats& s) {
  nlohmann::json j;
  j["rel_rms"] = s.rel_rms;
  j["max_abs"] = s.max_abs;
  j["psnr"] = std::isfinite(s.psnr) ? nlohmann::json(s.psnr) : nlohmann::json(nullptr);
  j["seconds"] = s.seconds;
  return j;
}

}  // namespace

ErrorStats CompareToReference(std::span<const float> image, std::span<const float> reference) {
  double sq = 0, ref_sq = 0, max_abs = 0, peak = 0;
  int64_t count = 0;
  for (size_t i = 0; i < reference.size(); ++i) {
    if (std::isnan(reference[i])) continue;  // masked cell
    const double d = double{image[i]} - reference[i];
    sq += d * d;
    ref_sq += double{reference[i]} * reference[i];
    max_abs = std::max(max_abs, std::fabs(d));
    peak = std::max(peak, double{reference[i]});
    ++count;
  }
  ErrorStats s;
  s.rel_rms = ref_sq > 0 ? std::sqrt(sq / ref_sq) : std::sqrt(sq);
  s.max_abs = max_abs;
  s.psnr = sq > 0 ? 10 * std::log10(peak * peak / (sq / count))
                  : std::numeric_limits<double>::infinity();
  return s;
}

absl::StatusOr<Scene> LoadBakedScene(const StoreInfo& info) {
  // Checked by content hash: a scene file edited since the bake would make
  // every comparison meaningless.
  absl::StatusOr<Scene> scene = LoadScene(info.scene_spec);
  if (!scene.ok()) return scene.status();
  const std::string hash = StoreSceneHash(info, *scene);
  if (!info.scene_hash.empty() && hash != info.scene_hash) {
    return absl::FailedPreconditionError(absl::StrCat("scene: ", info.scene_spec,
                                                      " no longer matches the baked scene (hash ",
                                                      hash, " vs ", info.scene_hash, ")"));
  }
  return scene;
}

absl::StatusOr<RayCaster> BuildBakedScene(const StoreInfo& info) {
  absl::StatusOr<Scene> scene = LoadBakedScene(info);
  if (!scene.ok()) return scene.status();
  return RayCaster::Build(*scene);
}

float BakedEpsilon(const StoreInfo& info, const RayCaster& caster) {
  return info.params.ray_epsilon > 0 ? info.params.ray_epsilon : caster.DefaultEpsilon();
}

absl::StatusOr<EvalReport> Evaluate(const std::filesystem::path& store, std::string_view env_spec,
                                    int terms, const EvalOptions& options) {
  if (terms <= 0) {
    return absl::InvalidArgumentError(absl::StrCat("terms: ", terms, "; need at least 1"));
  }
  absl::StatusOr<StoreInfo> store_info = ReadStoreInfo(store);
  if (!store_info.ok()) return store_info.status();
  if (store_info->params.transport == Transport::kVisibility) {
    if (options.bounces > 0)
      return absl::InvalidArgumentError(
          "bounces: a visibility store's glossy reference is direct light only (the triple "
          "product keeps visibility and the BRDF apart)");
    return EvaluateGlossy(store, env_spec, terms, options);
  }
  // A diffuse store is Lambertian by construction.
  absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(options.glossy.brdf);
  if (!brdf.ok()) return brdf.status();
  if ((*brdf)->Name() != "lambert") return CheckVisibilityStore(*store_info);
  absl::StatusOr<OpenedStore> opened = OpenStore(store);
  if (!opened.ok()) return opened.status();
  if (absl::Status s = RequireCubeDomain(opened->info); !s.ok()) return s;
  absl::StatusOr<EnvMap> env = LoadEnvMap(env_spec);
  if (!env.ok()) return env.status();
  if (options.rotate_degrees != 0) *env = Rotated(*env, options.rotate_degrees);

  const StoreInfo& info = opened->info;
  if (options.bounces > kMaxBounces)
    return absl::InvalidArgumentError(
        absl::StrCat("bounces: ", options.bounces, " is outside 0..", kMaxBounces));
  absl::StatusOr<Scene> scene = LoadBakedScene(info);
  if (!scene.ok()) return scene.status();
  absl::StatusOr<RayCaster> caster = RayCaster::Build(*scene);
  if (!caster.ok()) return caster.status();
  const float eps = BakedEpsilon(info, *caster);

  EvalReport report;
  report.terms = terms;
  // `auto` was resolved by the bake; the count it chose is in the record.
  report.store_bounces = info.params.bounces == kAutoBounces
                             ? info.attrs.value(nlohmann::json::json_pointer("/bounces/count"), 0)
                             : info.params.bounces;
  report.bounces = options.bounces >= 0 ? options.bounces : report.store_bounces;
  ReferenceOptions ref_options = options.reference;
  ref_options.epsilon = eps;
  // Direct light only: the direct reference, as before bounces existed.
  absl::StatusOr<ReferenceResult> reference =
      report.bounces == 0 ? ComputeReference(*caster, opened->samples, *env, ref_options)
                          : ComputePathReference(*scene, *caster, opened->samples, *env,
                                                 {.bounces = report.bounces,
                                                  .target_rel_se = ref_options.target_rel_se,
                                                  .seed = ref_options.seed,
                                                  .threads = ref_options.threads,
                                                  .epsilon = eps});
  if (!reference.ok()) return reference.status();
  report.reference_rel_se = reference->rel_se;
  report.reference_rays = reference->rays;
  report.reference_seconds = reference->seconds;
  report.reference_converged = reference->converged;

  auto t0 = std::chrono::steady_clock::now();
  absl::StatusOr<std::vector<float>> compressed = RelightImage(*opened, *env, terms);
  if (!compressed.ok()) return compressed.status();
  const double compressed_seconds = SecondsSince(t0);
  report.compressed = CompareToReference(*compressed, reference->rgb);
  report.compressed.seconds = compressed_seconds;

  // The dense retrace is the direct T: the uncompressed answer of a
  // 0-bounce store only.
  if (options.dense && report.store_bounces == 0) {
    t0 = std::chrono::steady_clock::now();
    const std::vector<float> cube = ResampleToCubemap(*env, Cubemap(info.light_res));
    DenseTraceOptions dense_options{info.light_res, info.params.supersample, info.params.seed, eps};
    absl::StatusOr<DenseTraceResult> dense =
        TraceDenseRelight(*caster, opened->samples, cube, dense_options);
    if (!dense.ok()) return dense.status();
    const double dense_seconds = SecondsSince(t0);
    report.dense = CompareToReference(dense->rgb, reference->rgb);
    report.dense.seconds = dense_seconds;
    report.has_dense = true;
    report.dense_rays = dense->rays;
  }
  return report;
}

nlohmann::json EvalReportJson(const EvalReport& r) {
  nlohmann::json j;
  j["terms"] = r.terms;
  j["dense"] = r.has_dense ? StatsJson(r.dense) : nlohmann::json(nullptr);
  j["compressed"] = StatsJson(r.compressed);
  j["reference"] = {{"rel_se", r.reference_rel_se},
                    {"rays", r.reference_rays},
                    {"seconds", r.reference_seconds},
                    {"converged", r.reference_converged},
                    {"bounces", r.bounces}};
  j["store_bounces"] = r.store_bounces;
  return j;
}

std::string EvalReportText(const EvalReport& r) {
  auto row = [](const char* name, const ErrorStats& e) {
    return absl::StrFormat("%-11s rel_rms %.5f  max_abs %.5g  psnr %6.2f dB  %.3f s\n", name,
                           e.rel_rms, e.max_abs, e.psnr, e.seconds);
  };
  std::string text = absl::StrFormat(
      "reference  rel_se %.5f  %d rays  %.1f s%s%s\n", r.reference_rel_se, r.reference_rays,
      r.reference_seconds, r.reference_converged ? "" : "  (NOT converged)",
      r.bounces > 0 || r.store_bounces > 0
          ? absl::StrFormat("  %d bounces (store: %d)", r.bounces, r.store_bounces)
          : std::string());
  if (r.has_dense) text += row("dense T", r.dense);
  return text + row("compressed", r.compressed);
}

}  // namespace wavebake
