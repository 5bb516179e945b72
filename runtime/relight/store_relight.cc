#include "runtime/relight/store_relight.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/layouts/layout.h"
#include "runtime/io/image_io.h"
#include "runtime/relight/finite_output.h"
#include "runtime/relight/lighting.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake {
namespace {

std::string LowerExtension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Per-vertex colours for a mesh layout: sample s colours global vertex
// samples.vertex[s]; vertices without a sample stay NaN (black in the PLY).
absl::Status WriteMeshColours(const StoreInfo& info, const SampleSet& s, std::span<const float> rgb,
                              float exposure_stops, const std::filesystem::path& out) {
  if (s.vertex.size() != s.position.size()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "out: ", out.string(), ": a .ply needs a mesh layout (grid|hilbert), the store has ",
        info.params.layout));
  }
  absl::StatusOr<Scene> scene = LoadScene(info.scene_spec);
  if (!scene.ok()) return scene.status();
  size_t vertices = 0;
  for (const Mesh& m : scene->meshes) vertices += m.positions.size();
  std::vector<float> colours(3 * vertices, std::numeric_limits<float>::quiet_NaN());
  for (size_t cell = 0; cell < s.grid.size(); ++cell) {
    const int32_t id = s.grid[cell];
    if (id < 0) continue;
    const size_t v = static_cast<size_t>(s.vertex[id]);
    if (v >= vertices) {
      return absl::InvalidArgumentError(
          absl::StrCat("samples/vertex: ", v, " outside the ", vertices, " vertices of the scene"));
    }
    for (int c = 0; c < 3; ++c) colours[3 * v + c] = rgb[3 * cell + c];
  }
  return WritePlyVertexColors(out, *scene, colours, exposure_stops);
}

}  // namespace

absl::StatusOr<OpenedStore> OpenStore(const std::filesystem::path& store) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  absl::StatusOr<SampleSet> samples = ReadSamples(store);
  if (!samples.ok()) return samples.status();
  absl::StatusOr<CompressedColumns> columns = ReadTransport(store);
  if (!columns.ok()) return columns.status();
  absl::StatusOr<Relighter> relighter = Relighter::Create(*columns, *samples);
  if (!relighter.ok()) return relighter.status();
  return OpenedStore{*std::move(info), *std::move(samples), *std::move(relighter)};
}

absl::Status RequireCubeDomain(const StoreInfo& info) {
  if (!info.params.light_domain.is_plane()) return absl::OkStatus();
  return absl::FailedPreconditionError(absl::StrCat(
      "store: light domain ", ToString(info.params.light_domain),
      " covers one face of directions, not an environment; relight it with --area-light"));
}

absl::StatusOr<std::vector<float>> RelightImage(OpenedStore& store, const EnvMap& env, int terms) {
  if (absl::Status s = RequireCubeDomain(store.info); !s.ok()) return s;
  Relighter& r = store.relighter;
  absl::StatusOr<LightingCoefficients> lighting =
      LightingFromEnv(env, r.light_res(), r.row_filter());
  if (!lighting.ok()) return lighting.status();
  absl::StatusOr<WaveletLights> lights = SelectWaveletLights(*lighting, terms);
  if (!lights.ok()) return lights.status();
  std::vector<float> rgb(3 * static_cast<size_t>(r.cells()));
  r.Relight(*lights, rgb);
  if (absl::Status s = CheckRelitFinite(rgb, store.samples.grid, store.samples.width,
                                        "the environment's radiance");
      !s.ok())
    return s;
  return rgb;
}

absl::Status CheckRelitPath(const std::filesystem::path& out) {
  const std::string ext = LowerExtension(out);
  if (ext == ".png" || ext == ".exr" || ext == ".ply" || ext == ".gltf" || ext == ".glb")
    return absl::OkStatus();
  return absl::InvalidArgumentError(
      absl::StrCat("out: ", out.string(), ": unknown extension (.png, .exr, .ply, .gltf, .glb)"));
}

absl::Status WriteRelit(const OpenedStore& store, std::span<const float> rgb, float exposure_stops,
                        const std::filesystem::path& out) {
  return WriteRelit(store.info, store.samples, rgb, exposure_stops, out);
}

absl::Status WriteRelit(const StoreInfo& info, const SampleSet& samples, std::span<const float> rgb,
                        float exposure_stops, const std::filesystem::path& out) {
  const std::string ext = LowerExtension(out);
  const int w = samples.width, h = samples.height;
  if (absl::Status s = CheckExposure(exposure_stops); !s.ok()) return s;
  // The last check before any export: whatever path produced `rgb`, a
  // non-finite value is not written as a picture.
  if (absl::Status s = CheckRelitFinite(rgb, samples.grid, w, "the lighting"); !s.ok()) return s;
  if (!samples.uv_charts.empty())
    return WriteLightmapOutput(info, samples, rgb, exposure_stops, out);
  if (ext == ".png") return WritePng(out, w, h, rgb, exposure_stops, Vec3{0, 0, 0});
  if (ext == ".exr") return WriteExr(out, w, h, rgb);
  if (ext == ".ply") return WriteMeshColours(info, samples, rgb, exposure_stops, out);
  return absl::InvalidArgumentError(
      absl::StrCat("out: ", out.string(),
                   ": unknown extension (.png, .exr or .ply; .gltf/.glb for uv layouts)"));
}

}  // namespace wavebake
