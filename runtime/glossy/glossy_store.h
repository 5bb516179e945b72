#pragma once
// Glossy relighting of a visibility store (DESIGN.md §1 "What a row holds",
// "Per-sample lighting"; §5 `relight --brdf`): the store's visibility rows
// decoded once (runtime/relight/sample_rows.h), the BRDF's slices for every sample's
// normal and view (runtime/glossy/brdf_slices.h) and the triple-product relighter
// (runtime/glossy/glossy_relighter.h), opened together.
//
// The view: camera layouts see every sample from the eye of the camera the
// layout was traced from (the scene's); mesh layouts (grid, hilbert, uv)
// take an eye position (`--view X,Y,Z`), needed as soon as the BRDF depends
// on the view.
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/directions/jitter_pattern.h"
#include "core/layouts/samples.h"
#include "core/products/brdf.h"
#include "runtime/env/env_map.h"
#include "runtime/glossy/brdf_slices.h"
#include "runtime/glossy/glossy_relighter.h"
#include "runtime/relight/sample_rows.h"
#include "storage/store_reader.h"

namespace wavebake {

struct GlossyOptions {
  std::string brdf = "lambert";  // ParseBrdf spelling
  std::optional<Vec3> eye;       // mesh layouts
  SliceOptions slices;           // BRDF terms per sample, quadrature, lobe cutoff
  int threads = 0;               // relighting threads; 0 = all cores
};

// "X,Y,Z" (three finite numbers); errors name the `view` flag.
absl::StatusOr<Vec3> ParseView(std::string_view spec);

// Per grid cell, the unit direction from the sample to the eye (masked
// cells: zero). Errors: an eye given for a camera layout, none for a mesh
// layout when `needed`.
absl::StatusOr<std::vector<Vec3>> ViewDirections(const StoreInfo& info, const SampleSet& samples,
                                                 std::optional<Vec3> eye, bool needed);

// The error for a store whose rows cannot feed the triple product, or OK.
absl::Status CheckVisibilityStore(const StoreInfo& info);

class GlossyStore {
 public:
  // Errors: not a visibility store (saying why), the BRDF spec, the view,
  // a damaged store.
  static absl::StatusOr<std::unique_ptr<GlossyStore>> Open(const std::filesystem::path& store,
                                                           const GlossyOptions& options);

  const StoreInfo& info() const { return info_; }
  const SampleSet& samples() const { return samples_; }
  const SampleRows& rows() const { return rows_; }
  const JitterPattern& pattern() const { return pattern_; }  // the slices' quadrature
  std::span<const Vec3> views() const { return views_; }
  const Brdf& brdf() const { return *brdf_; }
  GlossyRelighter& relighter() { return *relighter_; }

  // Reprojects the slices for another BRDF (material editing); the view
  // stays. Errors name the spec.
  absl::Status SetBrdf(std::string_view spec);
  // The slices `brdf` would have with these options (no state change).
  absl::StatusOr<BrdfSlices> Project(const Brdf& brdf, const SliceOptions& options) const;

  // × albedo, NaN in masked cells; `terms` area-weighted wavelet lights.
  absl::StatusOr<std::vector<float>> RelightImage(const EnvMap& env, int terms);

 private:
  GlossyStore() = default;
  StoreInfo info_;
  SampleSet samples_;
  SampleRows rows_;
  JitterPattern pattern_;
  std::vector<Vec3> views_;
  std::unique_ptr<Brdf> brdf_;
  GlossyOptions options_;
  std::optional<GlossyRelighter> relighter_;
};

// `wavebake relight STORE --brdf B …` for a visibility store: as RelightToFile
// (runtime/relight/store_relight.h), the image relit through the triple product.
absl::Status RelightGlossyToFile(const std::filesystem::path& store, std::string_view env_spec,
                                 int terms, double rotate_degrees, float exposure_stops,
                                 const std::filesystem::path& out, const GlossyOptions& options);

// `wavebake relight` for any store: a visibility store through the triple
// product with options.brdf; a diffuse store by Eq. 8 (RelightToFile), which
// accepts lambert only and no eye (an error says why).
absl::Status RelightStoreToFile(const std::filesystem::path& store, std::string_view env_spec,
                                int terms, double rotate_degrees, float exposure_stops,
                                const std::filesystem::path& out, const GlossyOptions& options);

}  // namespace wavebake
