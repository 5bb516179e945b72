#include "storage/scene_files/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/scene/builtin_scenes.h"
#include "storage/scene_files/scene_loader_parts.h"

namespace wavebake {
namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";

bool HasJsonExtension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".json";
}

absl::StatusOr<Scene> ReadScene(std::string_view spec, const SceneFiles& files,
                                std::vector<std::string>& warnings) {
  if (spec.starts_with(kBuiltinPrefix)) return MakeBuiltinScene(spec.substr(kBuiltinPrefix.size()));
  const std::filesystem::path path{std::string(spec)};
  if (HasJsonExtension(path)) return ReadJsonScene(path, files, warnings);
  absl::StatusOr<std::vector<Mesh>> meshes = ReadMeshFile(path, files);
  if (!meshes.ok()) return meshes.status();
  return Scene{.name = path.stem().string(), .meshes = *std::move(meshes), .camera = {}};
}

}  // namespace

absl::StatusOr<Scene> LoadScene(std::string_view spec, SceneReport* report,
                                const SceneFiles* files) {
  if (spec.empty())
    return absl::InvalidArgumentError("scene: empty (builtin:NAME, a mesh or a .json)");
  std::unique_ptr<SceneFiles> local;
  if (files == nullptr) files = (local = LocalSceneFiles()).get();
  std::vector<std::string> warnings;
  absl::StatusOr<Scene> scene = ReadScene(spec, *files, warnings);
  if (!scene.ok()) return scene.status();
  if (absl::Status s = CheckAndRepairScene(*scene, report); !s.ok())
    return absl::Status(
        s.code(), absl::StrCat("scene '", files->Name(std::string(spec)), "': ", s.message()));
  if (report != nullptr)
    report->warnings.insert(report->warnings.begin(), warnings.begin(), warnings.end());
  return scene;
}

}  // namespace wavebake
