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
#include "storage/store/store_reader.h"

namespace wavebake {

struct GlossyOptions {
  std::string brdf = "lambert";  // ParseBrdf spelling
  std::optional<Vec3> eye;       // mesh layouts
  SliceOptions slices;           // BRDF terms per sample, quadrature, lobe cutoff
  int threads = 0;               // relighting threads; 0 = all cores
};

// "X,Y,Z" (three finite numbers of magnitude ≤ kMaxEyeCoordinate, so that
// they are floats and eye − sample stays finite); errors name the `view` flag.
inline constexpr double kMaxEyeCoordinate = 1e30;
absl::StatusOr<Vec3> ParseView(std::string_view spec);

// The unit direction from `from` to `eye`, computed without overflow for any
// finite floats (double, scaled by the largest component); `fallback` when
// they coincide.
Vec3 UnitTowards(Vec3 eye, Vec3 from, Vec3 fallback);

// Per grid cell, the unit direction from the sample to the eye (masked
// cells: zero). Errors: an eye given for a camera layout, none for a mesh
// layout when `needed`.
absl::StatusOr<std::vector<Vec3>> ViewDirections(const StoreInfo& info, const SampleSet& samples,
                                                 std::optional<Vec3> eye, bool needed);

// Whether the store's cubemap (N texels per face edge) can hold the BRDF's
// lobe. The widest texel, at a face's centre, spans atan(2/N) (the face is
// [−1, 1]² at distance 1, cut into N); a lobe narrower than that lives
// inside one texel: its texel means smear it over the texel, the lighting is
// averaged over the texel, and the Q jittered quadrature points per texel
// (runtime/glossy/brdf_slices.h) hit its peak or miss it — at N = 32, ggx:0.001
// relit 264 % off the reference and ggx:1e-8 1.5e10 times too bright; at
// N = 8, ggx:1e-8 was black. Refused (InvalidArgument naming `brdf`, the
// width, the texel and the sharpest accepted parameter) when the lobe's full
// width at half maximum at normal incidence,
//   FWHM = 2·acos(Brdf::Support(n, n, ½).cos_angle)
//        ≈ 2.57 α (ggx: 4·atan(α·√(√2 − 1))), 2.35/√E (phong), 4.71/√E (blinn),
// is below atan(2/N): ggx needs α ≥ 0.095 at N = 8, 0.024 at N = 32 (≈ 0.78/N),
// phong E ≤ 92, 1423 (≈ 1.39 N²), blinn E ≤ 369, 5693 (≈ 5.6 N²).
absl::Status CheckBrdfResolvable(const Brdf& brdf, int light_res);

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

}  // namespace wavebake
