#include "runtime/reference/eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/directions/cubemap.h"
#include "core/scene/scene_hash.h"
#include "runtime/env/env_resample.h"
#include "runtime/reference/bounce_eval.h"
#include "runtime/reference/dense_trace.h"
#include "runtime/reference/glossy_eval.h"
#include "runtime/relight/store_relight.h"
#include "storage/scene_files/scene_loader.h"

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
  if (!std::isfinite(sq) || !std::isfinite(ref_sq)) {
    // A NaN difference used to vanish in max() and in "sq > 0", scoring a
    // NaN image as identical (psnr inf).
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.rel_rms = s.max_abs = s.psnr = nan;
    return s;
  }
  s.rel_rms = ref_sq > 0 ? std::sqrt(sq / ref_sq) : std::sqrt(sq);
  s.max_abs = max_abs;
  s.psnr = sq > 0 ? 10 * std::log10(peak * peak / (sq / count))
                  : std::numeric_limits<double>::infinity();
  return s;
}

absl::StatusOr<ErrorStats> CompareFinite(std::span<const float> image,
                                         std::span<const float> reference, std::string_view what) {
  if (image.size() != reference.size())
    return absl::InternalError(absl::StrCat(std::string(what), ": ", image.size(),
                                            " values against ", reference.size(),
                                            " of the reference"));
  for (size_t i = 0; i < reference.size(); ++i) {
    if (std::isnan(reference[i])) continue;  // masked cell
    const bool ref_bad = !std::isfinite(reference[i]);
    if (ref_bad || !std::isfinite(image[i])) {
      const float v = ref_bad ? reference[i] : image[i];
      return absl::InvalidArgumentError(absl::StrCat(
          ref_bad ? "the reference" : std::string(what), ": value ", i % 3, " of cell ", i / 3,
          " is ", std::isnan(v) ? "NaN" : "infinite",
          "; the lighting overflowed single precision, no error can be measured (scale the "
          "lighting down)"));
    }
  }
  return CompareToReference(image, reference);
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

absl::StatusOr<EvalReport> CompareWithReference(const RayCaster& caster, const SampleSet& samples,
                                                const EnvMap& env,
                                                const ReferenceOptions& ref_options, int terms,
                                                const ImageFn& compressed, const DenseFn& dense) {
  absl::StatusOr<ReferenceResult> reference = ComputeReference(caster, samples, env, ref_options);
  if (!reference.ok()) return reference.status();
  return CompareWithReference(*reference, terms, compressed, dense);
}

absl::StatusOr<EvalReport> CompareWithReference(const ReferenceResult& result, int terms,
                                                const ImageFn& compressed, const DenseFn& dense) {
  EvalReport report;
  report.terms = terms;
  const ReferenceResult* reference = &result;
  report.reference_rel_se = reference->rel_se;
  report.reference_rays = reference->rays;
  report.reference_seconds = reference->seconds;
  report.reference_converged = reference->converged;

  auto t0 = std::chrono::steady_clock::now();
  absl::StatusOr<std::vector<float>> image = compressed();
  if (!image.ok()) return image.status();
  const double compressed_seconds = SecondsSince(t0);
  absl::StatusOr<ErrorStats> compressed_error =
      CompareFinite(*image, reference->rgb, "the compressed relighting");
  if (!compressed_error.ok()) return compressed_error.status();
  report.compressed = *compressed_error;
  report.compressed.seconds = compressed_seconds;

  if (dense) {
    t0 = std::chrono::steady_clock::now();
    absl::StatusOr<DenseTraceResult> traced = dense();
    if (!traced.ok()) return traced.status();
    const double dense_seconds = SecondsSince(t0);
    absl::StatusOr<ErrorStats> dense_error =
        CompareFinite(traced->rgb, reference->rgb, "the dense relighting");
    if (!dense_error.ok()) return dense_error.status();
    report.dense = *dense_error;
    report.dense.seconds = dense_seconds;
    report.has_dense = true;
    report.dense_rays = traced->rays;
  }
  return report;
}

absl::StatusOr<EvalReport> Evaluate(const std::filesystem::path& store, const EnvMap& env_map,
                                    int terms, const EvalOptions& options) {
  if (terms <= 0) {
    return absl::InvalidArgumentError(absl::StrCat("terms: ", terms, "; need at least 1"));
  }
  // Rotated leaves the map as it is for a non-finite angle: refused here, or
  // the report would be of an unrotated environment.
  if (!std::isfinite(options.rotate_degrees))
    return absl::InvalidArgumentError(
        absl::StrCat("rotate: ", options.rotate_degrees, " is not finite"));
  absl::StatusOr<StoreInfo> store_info = ReadStoreInfo(store);
  if (!store_info.ok()) return store_info.status();
  if (store_info->params.transport == Transport::kVisibility) {
    if (options.bounces > 0)
      return absl::InvalidArgumentError(
          "bounces: a visibility store's glossy reference is direct light only (the triple "
          "product keeps visibility and the BRDF apart, so bounced light is not in the store)");
    return EvaluateGlossy(store, env_map, terms, options);
  }
  // A diffuse store is Lambertian by construction.
  absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(options.glossy.brdf);
  if (!brdf.ok()) return brdf.status();
  if ((*brdf)->Name() != "lambert") return CheckVisibilityStore(*store_info);
  absl::StatusOr<OpenedStore> opened = OpenStore(store);
  if (!opened.ok()) return opened.status();
  if (absl::Status s = RequireCubeDomain(opened->info); !s.ok()) return s;
  std::optional<EnvMap> turned;
  if (options.rotate_degrees != 0) turned = Rotated(env_map, options.rotate_degrees);
  const EnvMap& env = turned ? *turned : env_map;

  const StoreInfo& info = opened->info;
  if (info.params.bounces != 0 || options.bounces > 0)
    return EvaluateBounces(*opened, env, terms, options);
  absl::StatusOr<RayCaster> caster = BuildBakedScene(info);
  if (!caster.ok()) return caster.status();
  const float eps = BakedEpsilon(info, *caster);
  ReferenceOptions ref_options = options.reference;
  ref_options.epsilon = eps;
  DenseFn dense;
  if (options.dense) {
    dense = [&]() -> absl::StatusOr<DenseTraceResult> {
      const std::vector<float> cube = ResampleToCubemap(env, Cubemap(info.light_res));
      DenseTraceOptions dense_options{info.light_res, info.params.supersample, info.params.seed,
                                      eps};
      return TraceDenseRelight(*caster, opened->samples, cube, dense_options);
    };
  }
  return CompareWithReference(
      *caster, opened->samples, env, ref_options, terms,
      [&] { return RelightImage(*opened, env, terms); }, dense);
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
  j["direct"] = r.has_direct ? StatsJson(r.direct) : nlohmann::json(nullptr);
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
  // A bounce store's direct light alone: what leaving the bounces out costs.
  if (r.has_direct) text += row("0 bounces", r.direct);
  if (r.has_dense) text += row("dense T", r.dense);
  return text + row("compressed", r.compressed);
}

}  // namespace wavebake
