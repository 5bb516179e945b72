#pragma once
// The measurement behind `wavebake eval STORE --env ENV --reference` (DESIGN.md
// §5; the command: driver/eval/evaluate.h): how far the store's relighting is from
// an independently traced reference (runtime/reference/reference.h), next to
// how far the uncompressed T is (runtime/reference/dense_trace.h), so
// discretization and compression error can be told apart.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "core/transport/ray_caster.h"
#include "runtime/env/env_map.h"
#include "runtime/glossy/glossy_store.h"
#include "runtime/reference/dense_trace.h"
#include "runtime/reference/reference.h"
#include "storage/store/store_reader.h"

namespace wavebake {

struct EvalOptions {
  ReferenceOptions reference;  // its epsilon is replaced by the bake's
  double rotate_degrees = 0;   // environment rotation about +Y (Rotated)
  bool dense = true;           // also retrace and evaluate the uncompressed T
  // The material. A visibility store is relit through the triple product
  // (runtime/reference/glossy_eval.h) with this BRDF, its reference traced with it; a
  // diffuse store takes lambert only (anything else is an error saying why).
  GlossyOptions glossy;
  // Diffuse bounces of the reference: < 0 the store's own count; a count
  // above 0 traces the path-traced reference (runtime/reference/path_reference.h),
  // so a 0-bounce store can be held against the light it leaves out.
  int bounces = -1;
};

// Over all unmasked cells and the three channels of image vs reference:
//   rel_rms = sqrt(Σ (x − r)² / Σ r²),  max_abs = max |x − r|,
//   psnr = 10 log10(peak² / mean (x − r)²) dB with peak = max r
// (+inf when identical: JSON null). seconds: wall time of producing the image.
struct ErrorStats {
  double rel_rms = 0, max_abs = 0, psnr = 0, seconds = 0;
};
// A NaN or infinite image value where the reference has one, or an infinite
// reference value, makes every field NaN (never a perfect score).
ErrorStats CompareToReference(std::span<const float> image, std::span<const float> reference);
// The same where a number is reported (eval, sequences' errors.csv, Python):
// InvalidArgument instead of any non-finite input, naming the cell and
// whether `what` (the image: "the compressed relighting") or the reference
// holds it.
absl::StatusOr<ErrorStats> CompareFinite(std::span<const float> image,
                                         std::span<const float> reference, std::string_view what);

// The scene a store was baked from; FailedPrecondition if its file no longer
// hashes to the baked scene.
absl::StatusOr<Scene> LoadBakedScene(const StoreInfo& info);
// The same, rebuilt for ray casting.
absl::StatusOr<RayCaster> BuildBakedScene(const StoreInfo& info);
// The ray offset the bake used (its own, or the scene's default).
float BakedEpsilon(const StoreInfo& info, const RayCaster& caster);

struct EvalReport {
  int terms = 0;
  // compressed.seconds: lighting (resample, row transform, selection) +
  // Eq. 8 relight, the store already in memory. dense.seconds: retracing
  // every row of T and the product with L (the cost of the answer without a
  // store).
  ErrorStats dense, compressed;
  bool has_dense = false;
  double reference_rel_se = 0;  // the reference's own error in the rel_rms metric
  int64_t reference_rays = 0;
  double reference_seconds = 0;
  bool reference_converged = true;
  int64_t dense_rays = 0;
  int bounces = 0;        // of the reference
  int store_bounces = 0;  // of the store
  // A store with bounces: its direct light alone (dense T₀, what a 0-bounce
  // bake would hold uncompressed) against the same reference, beside the
  // dense answer with the store's bounces (runtime/reference/bounce_eval.h).
  ErrorStats direct;
  bool has_direct = false;
};

// The store relit under env (lat-long, turned by options.rotate_degrees)
// against the reference. Errors: terms ≤ 0; the store (missing, another
// format version, damaged); the scene spec recorded in the store no longer
// loading or no longer hashing to the baked scene.
absl::StatusOr<EvalReport> Evaluate(const std::filesystem::path& store, const EnvMap& env,
                                    int terms, const EvalOptions& options = {});

// What both stores' evals share: the reference traced over `samples` under
// env, then the store's image (`compressed`) and, when `dense` is given, the
// uncompressed answer, each timed and compared with the reference.
using ImageFn = std::function<absl::StatusOr<std::vector<float>>()>;
using DenseFn = std::function<absl::StatusOr<DenseTraceResult>()>;
absl::StatusOr<EvalReport> CompareWithReference(const RayCaster& caster, const SampleSet& samples,
                                                const EnvMap& env,
                                                const ReferenceOptions& ref_options, int terms,
                                                const ImageFn& compressed, const DenseFn& dense);
// The same against a reference already traced.
absl::StatusOr<EvalReport> CompareWithReference(const ReferenceResult& reference, int terms,
                                                const ImageFn& compressed, const DenseFn& dense);

// {"terms": n, "dense": {"rel_rms", "max_abs", "psnr", "seconds"},
//  "compressed": {same keys}, "reference": {"rel_se", "rays", "seconds",
//  "converged", "bounces"}, "store_bounces": B, "direct": {same keys} or
//  null}; "dense" is null when not evaluated.
nlohmann::json EvalReportJson(const EvalReport& report);
// The same for a person: the reference's line, then dense T's and the
// store's (rel_rms, max_abs, psnr, seconds), one line each.
std::string EvalReportText(const EvalReport& report);

}  // namespace wavebake
