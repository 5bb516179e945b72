#pragma once
// `wavebake eval STORE --env ENV --reference [--terms n] [--json]`
// (DESIGN.md §5): how far the store's relighting is from an independently
// traced reference (runtime/reference.h), next to how far the uncompressed T
// is (runtime/dense_trace.h), so discretization and compression error can be
// told apart.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/ray_caster.h"
#include "runtime/glossy_store.h"
#include "runtime/reference.h"
#include "storage/store_reader.h"

namespace wavebake {

struct EvalOptions {
  ReferenceOptions reference;  // its epsilon is replaced by the bake's
  double rotate_degrees = 0;   // environment rotation about +Y (Rotated)
  bool dense = true;           // also retrace and evaluate the uncompressed T
  // The material. A visibility store is relit through the triple product
  // (runtime/glossy_eval.h) with this BRDF, its reference traced with it; a
  // diffuse store takes lambert only (anything else is an error saying why).
  GlossyOptions glossy;
  // Diffuse bounces of the reference: < 0 the store's own count; a count
  // above 0 traces the path-traced reference (runtime/path_reference.h), so
  // a 0-bounce store can be held against the light it leaves out.
  int bounces = -1;
};

// Over all unmasked cells and the three channels of image vs reference:
//   rel_rms = sqrt(Σ (x − r)² / Σ r²),  max_abs = max |x − r|,
//   psnr = 10 log10(peak² / mean (x − r)²) dB with peak = max r
// (+inf when identical: JSON null). seconds: wall time of producing the image.
struct ErrorStats {
  double rel_rms = 0, max_abs = 0, psnr = 0, seconds = 0;
};
ErrorStats CompareToReference(std::span<const float> image, std::span<const float> reference);

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
  int store_bounces = 0;  // of the store (dense T is retraced only for 0: it is direct light)
};

// Errors: terms ≤ 0; the store (missing, another format version, damaged);
// the env spec; the scene spec recorded in the store no longer loading or no
// longer hashing to the baked scene.
absl::StatusOr<EvalReport> Evaluate(const std::filesystem::path& store, std::string_view env_spec,
                                    int terms, const EvalOptions& options = {});

// {"terms": n, "dense": {"rel_rms", "max_abs", "psnr", "seconds"},
//  "compressed": {same keys}, "reference": {"rel_se", "rays", "seconds",
//  "converged", "bounces"}, "store_bounces": B}; "dense" is null when not
//  evaluated.
nlohmann::json EvalReportJson(const EvalReport& report);
// The same for a person: the reference's line, then dense T's and the
// store's (rel_rms, max_abs, psnr, seconds), one line each.
std::string EvalReportText(const EvalReport& report);

}  // namespace wavebake
