#include "runtime/glossy/glossy_store.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "core/bake/bake_params_io.h"
#include "core/directions/cubemap.h"
#include "core/layouts/layout.h"
#include "runtime/relight/finite_output.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake {

Vec3 UnitTowards(Vec3 eye, Vec3 from, Vec3 fallback) {
  // In double, scaled by the largest component before the length: |d|² in
  // float overflowed for an eye 3e19 away (inf length, a zero direction).
  const double d[3] = {double(eye.x) - from.x, double(eye.y) - from.y, double(eye.z) - from.z};
  const double m = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])});
  if (!(m > 0) || !std::isfinite(m)) return fallback;
  const double x = d[0] / m, y = d[1] / m, z = d[2] / m;
  const double len = std::sqrt(x * x + y * y + z * z);
  return Vec3{float(x / len), float(y / len), float(z / len)};
}

absl::StatusOr<Vec3> ParseView(std::string_view spec) {
  const std::vector<std::string> parts = absl::StrSplit(std::string(spec), ',');
  double v[3];
  if (parts.size() != 3 || !absl::SimpleAtod(parts[0], &v[0]) ||
      !absl::SimpleAtod(parts[1], &v[1]) || !absl::SimpleAtod(parts[2], &v[2]) ||
      !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
    return absl::InvalidArgumentError(absl::StrCat(
        "view: '", std::string(spec), "' is not an eye position X,Y,Z of three finite numbers"));
  }
  // float(1e308) is inf, and every view direction became 0 (all-black, rc 0).
  for (int i = 0; i < 3; ++i) {
    if (std::fabs(v[i]) > kMaxEyeCoordinate)
      return absl::InvalidArgumentError(absl::StrCat("view: '", std::string(spec), "': ", v[i],
                                                     " is beyond ±", kMaxEyeCoordinate,
                                                     " scene units"));
  }
  return Vec3{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

namespace {

double LobeFullWidth(const Brdf& brdf) {
  const Vec3 n{0, 0, 1};
  const LobeCone cone = brdf.Support(n, n, 0.5);
  return 2 * std::acos(std::clamp(double(cone.cos_angle), -1.0, 1.0));
}

// The sharpest parameter of the BRDF's kind whose lobe still spans `texel`
// (bisection on the model itself: no closed form to keep in step with it).
std::string SharpestAccepted(const Brdf& brdf, double texel) {
  const std::string name = brdf.Name();
  const std::string kind = name.substr(0, name.find(':'));
  const bool roughness = kind == "ggx";
  double lo = roughness ? 1e-9 : 1e-3, hi = roughness ? 1.0 : 1e9;  // lobe width falls lo→hi
  if (roughness) std::swap(lo, hi);                                 // ggx: wider with larger α
  for (int i = 0; i < 100; ++i) {
    const double mid = std::sqrt(lo * hi);
    absl::StatusOr<std::unique_ptr<Brdf>> b = ParseBrdf(absl::StrCat(kind, ":", mid));
    if (b.ok() && LobeFullWidth(**b) >= texel) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return absl::StrCat(kind, roughness ? ": roughness ≥ " : ": exponent ≤ ",
                      absl::StrFormat("%.3g", lo));
}

}  // namespace

absl::Status CheckBrdfResolvable(const Brdf& brdf, int light_res) {
  const double texel = std::atan(2.0 / light_res);
  const double width = LobeFullWidth(brdf);
  if (width >= texel) return absl::OkStatus();
  constexpr double kDegrees = 180 / std::numbers::pi;
  return absl::InvalidArgumentError(absl::StrFormat(
      "brdf: '%s' has a lobe %.3g° wide at half maximum, narrower than a texel (%.3g°) of the "
      "store's N = %d cubemap, which cannot represent it (the relit result would be noise or "
      "black); at this N use %s, or bake with a larger --light-res",
      brdf.Name(), width * kDegrees, texel * kDegrees, light_res, SharpestAccepted(brdf, texel)));
}

absl::Status CheckVisibilityStore(const StoreInfo& info) {
  if (info.params.transport == Transport::kVisibility) return absl::OkStatus();
  return absl::FailedPreconditionError(absl::StrCat(
      "store: its rows hold the diffuse transport T = V·cos/π, with the Lambertian BRDF folded "
      "into every row, so no other BRDF can be applied to it; bake the scene with --transport "
      "visibility (rows of V alone, the BRDF applied at relight time) for glossy relighting"));
}

absl::StatusOr<std::vector<Vec3>> ViewDirections(const StoreInfo& info, const SampleSet& samples,
                                                 std::optional<Vec3> eye, bool needed) {
  absl::StatusOr<LayoutSpec> layout = ParseLayout(info.params.layout);
  if (!layout.ok()) return layout.status();
  if (layout->kind == LayoutKind::kCamera) {
    if (eye) {
      return absl::InvalidArgumentError(
          "view: a camera layout sees every sample from its baked camera; --view is for mesh "
          "layouts");
    }
    absl::StatusOr<Scene> scene = LoadScene(info.scene_spec);
    if (!scene.ok()) return scene.status();
    if (!scene->camera)
      return absl::FailedPreconditionError(
          absl::StrCat("scene: ", info.scene_spec, " has no camera for the camera layout"));
    eye = scene->camera->eye;
  } else if (!eye) {
    if (needed) {
      return absl::InvalidArgumentError(
          absl::StrCat("view: a ", info.params.layout,
                       " layout has no camera; give the eye position with --view X,Y,Z"));
    }
    eye = Vec3{0, 0, 0};  // any: the BRDF ignores the view
  }
  std::vector<Vec3> views(samples.cells(), Vec3{0, 0, 0});
  for (int cell = 0; cell < samples.cells(); ++cell) {
    const int32_t s = samples.grid[cell];
    if (s < 0) continue;
    views[cell] = UnitTowards(*eye, samples.position[s], samples.normal[s]);
  }
  return views;
}

absl::StatusOr<std::unique_ptr<GlossyStore>> GlossyStore::Open(const std::filesystem::path& store,
                                                               const GlossyOptions& options) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  if (absl::Status s = CheckVisibilityStore(*info); !s.ok()) return s;
  absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(options.brdf);
  if (!brdf.ok()) return brdf.status();
  if (absl::Status s = CheckBrdfResolvable(**brdf, info->light_res); !s.ok()) return s;
  absl::StatusOr<SampleSet> samples = ReadSamples(store);
  if (!samples.ok()) return samples.status();
  absl::StatusOr<std::vector<Vec3>> views =
      ViewDirections(*info, *samples, options.eye, (*brdf)->ViewDependent());
  if (!views.ok()) return views.status();
  absl::StatusOr<CompressedColumns> columns = ReadTransport(store);
  if (!columns.ok()) return columns.status();
  absl::StatusOr<SampleRows> rows = SampleRows::Decode(*columns);
  if (!rows.ok()) return rows.status();
  absl::StatusOr<JitterPattern> pattern =
      BrdfQuadrature(info->light_res, info->params.supersample, info->params.seed, options.slices);
  if (!pattern.ok()) return pattern.status();

  std::unique_ptr<GlossyStore> g(new GlossyStore());
  g->info_ = *std::move(info);
  g->samples_ = *std::move(samples);
  g->rows_ = *std::move(rows);
  g->pattern_ = *std::move(pattern);
  g->views_ = *std::move(views);
  g->brdf_ = *std::move(brdf);
  g->options_ = options;
  absl::StatusOr<BrdfSlices> slices = g->Project(*g->brdf_, options.slices);
  if (!slices.ok()) return slices.status();
  absl::StatusOr<GlossyRelighter> relighter =
      GlossyRelighter::Create(&g->rows_, g->samples_, *std::move(slices), options.threads);
  if (!relighter.ok()) return relighter.status();
  g->relighter_.emplace(*std::move(relighter));
  return g;
}

absl::StatusOr<BrdfSlices> GlossyStore::Project(const Brdf& brdf,
                                                const SliceOptions& options) const {
  return ProjectBrdfSlices(brdf, samples_, views_, pattern_, options);
}

absl::Status GlossyStore::SetBrdf(std::string_view spec) {
  absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(spec);
  if (!brdf.ok()) return brdf.status();
  if (absl::Status s = CheckBrdfResolvable(**brdf, info_.light_res); !s.ok()) return s;
  absl::StatusOr<BrdfSlices> slices = Project(**brdf, options_.slices);
  if (!slices.ok()) return slices.status();
  if (absl::Status s = relighter_->SetSlices(*std::move(slices)); !s.ok()) return s;
  brdf_ = *std::move(brdf);
  return absl::OkStatus();
}

absl::StatusOr<std::vector<float>> GlossyStore::RelightImage(const EnvMap& env, int terms) {
  absl::StatusOr<LightingCoefficients> lighting =
      LightingFromEnv(env, info_.light_res, WaveletFilter::kHaar);
  if (!lighting.ok()) return lighting.status();
  absl::StatusOr<WaveletLights> lights = SelectWaveletLights(*lighting, terms);
  if (!lights.ok()) return lights.status();
  std::vector<float> rgb(3 * static_cast<size_t>(samples_.cells()));
  relighter_->Relight(*lights, rgb);
  if (absl::Status s =
          CheckRelitFinite(rgb, samples_.grid, samples_.width, "the environment's radiance");
      !s.ok())
    return s;
  return rgb;
}

}  // namespace wavebake
