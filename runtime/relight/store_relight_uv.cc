// WriteLightmapOutput of store_relight.h: what relighting a uv store writes.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/layouts/layout.h"
#include "runtime/io/image_io.h"
#include "runtime/io/lightmap.h"
#include "runtime/relight/store_relight.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake {
namespace {

// The baked scene, reloaded and checked against the store's scene hash.
absl::StatusOr<Scene> BakedScene(const StoreInfo& info) {
  absl::StatusOr<Scene> scene = LoadScene(info.scene_spec);
  if (!scene.ok()) return scene.status();
  const std::string hash = StoreSceneHash(info, *scene);
  if (!info.scene_hash.empty() && hash != info.scene_hash)
    return absl::FailedPreconditionError(absl::StrCat("scene: ", info.scene_spec,
                                                      " no longer matches the baked scene (hash ",
                                                      hash, " vs ", info.scene_hash, ")"));
  return scene;
}

}  // namespace

absl::Status WriteLightmapOutput(const StoreInfo& info, const SampleSet& s,
                                 std::span<const float> rgb, float exposure_stops,
                                 const std::filesystem::path& out) {
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::vector<float> lightmap = DilateGutters(s, rgb);
  if (ext == ".png") return WritePng(out, s.width, s.height, lightmap, exposure_stops, Vec3{});
  if (ext == ".exr") {
    for (float& v : lightmap)
      if (std::isnan(v)) v = 0;
    return WriteExr(out, s.width, s.height, lightmap);
  }
  if (ext != ".gltf" && ext != ".glb")
    return absl::InvalidArgumentError(
        absl::StrCat("out: ", out.string(),
                     ": a uv store writes .png or .exr lightmaps, or a "
                     ".gltf/.glb mesh with its lightmap"));
  absl::StatusOr<LayoutSpec> layout = ParseLayout(info.params.layout);
  if (!layout.ok()) return layout.status();
  absl::StatusOr<Scene> scene = BakedScene(info);
  if (!scene.ok()) return scene.status();
  absl::StatusOr<std::vector<std::vector<Vec2>>> uvs = LightmapUvs(*scene, s, layout->uv_channel);
  if (!uvs.ok()) return uvs.status();
  absl::StatusOr<std::vector<std::byte>> png =
      EncodePng(s.width, s.height, lightmap, exposure_stops, Vec3{});
  if (!png.ok()) return png.status();
  return WriteLightmapGltf(out, *scene, *uvs, *png);
}

absl::StatusOr<LightmapMesh> LightmapMeshOf(const StoreInfo& info, const SampleSet& s) {
  absl::StatusOr<LayoutSpec> layout = ParseLayout(info.params.layout);
  if (!layout.ok()) return layout.status();
  if (layout->kind != LayoutKind::kUv)
    return absl::FailedPreconditionError(
        absl::StrCat("store: layout ", info.params.layout, " is not a uv lightmap"));
  absl::StatusOr<Scene> scene = BakedScene(info);
  if (!scene.ok()) return scene.status();
  absl::StatusOr<std::vector<std::vector<Vec2>>> uvs = LightmapUvs(*scene, s, layout->uv_channel);
  if (!uvs.ok()) return uvs.status();
  LightmapMesh out;
  for (size_t i = 0; i < scene->meshes.size(); ++i) {
    const Mesh& m = scene->meshes[i];
    const uint32_t base = static_cast<uint32_t>(out.positions.size() / 3);
    for (size_t v = 0; v < m.positions.size(); ++v) {
      out.positions.insert(out.positions.end(),
                           {m.positions[v].x, m.positions[v].y, m.positions[v].z});
      const Vec2 uv = (*uvs)[i][v];
      out.texels.insert(out.texels.end(), {uv.u * float(s.width), (1.0f - uv.v) * float(s.height)});
    }
    for (const auto& t : m.triangles)
      out.indices.insert(out.indices.end(), {base + t[0], base + t[1], base + t[2]});
  }
  return out;
}

}  // namespace wavebake
