#include "runtime/glossy/glossy_store.h"

#include <cmath>
#include <string>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "core/bake/bake_params_io.h"
#include "core/directions/cubemap.h"
#include "core/layouts/layout.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"
#include "storage/scene_loader.h"

namespace wavebake {

absl::StatusOr<Vec3> ParseView(std::string_view spec) {
  const std::vector<std::string> parts = absl::StrSplit(std::string(spec), ',');
  double v[3];
  if (parts.size() != 3 || !absl::SimpleAtod(parts[0], &v[0]) ||
      !absl::SimpleAtod(parts[1], &v[1]) || !absl::SimpleAtod(parts[2], &v[2]) ||
      !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
    return absl::InvalidArgumentError(absl::StrCat(
        "view: '", std::string(spec), "' is not an eye position X,Y,Z of three finite numbers"));
  }
  return Vec3{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
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
    const Vec3 d = *eye - samples.position[s];
    const float len = Length(d);
    views[cell] = len > 0 ? d / len : samples.normal[s];
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
  return rgb;
}

absl::Status RelightGlossyToFile(const std::filesystem::path& store, std::string_view env_spec,
                                 int terms, double rotate_degrees, float exposure_stops,
                                 const std::filesystem::path& out, const GlossyOptions& options) {
  if (terms <= 0)
    return absl::InvalidArgumentError(absl::StrCat("terms: ", terms, "; need at least 1"));
  if (!std::isfinite(rotate_degrees))
    return absl::InvalidArgumentError(absl::StrCat("rotate: ", rotate_degrees, " is not finite"));
  absl::StatusOr<EnvMap> env = LoadEnvMap(env_spec);
  if (!env.ok()) return env.status();
  if (rotate_degrees != 0) *env = Rotated(*env, rotate_degrees);
  absl::StatusOr<std::unique_ptr<GlossyStore>> g = GlossyStore::Open(store, options);
  if (!g.ok()) return g.status();
  absl::StatusOr<std::vector<float>> rgb = (*g)->RelightImage(*env, terms);
  if (!rgb.ok()) return rgb.status();
  return WriteRelit((*g)->info(), (*g)->samples(), *rgb, exposure_stops, out);
}

absl::Status RelightStoreToFile(const std::filesystem::path& store, std::string_view env_spec,
                                int terms, double rotate_degrees, float exposure_stops,
                                const std::filesystem::path& out, const GlossyOptions& options) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  if (info->params.transport == Transport::kVisibility)
    return RelightGlossyToFile(store, env_spec, terms, rotate_degrees, exposure_stops, out,
                               options);
  absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(options.brdf);
  if (!brdf.ok()) return brdf.status();
  if ((*brdf)->Name() != "lambert") return CheckVisibilityStore(*info);
  if (options.eye)
    return absl::InvalidArgumentError(
        "view: a diffuse store is relit the same from every view; --view needs a visibility "
        "store and a glossy --brdf");
  return RelightToFile(store, env_spec, terms, rotate_degrees, exposure_stops, out);
}

}  // namespace wavebake
