#pragma once
// SCENE argument of DESIGN.md §5 → a checked Scene.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "core/scene/scene_check.h"
#include "storage/scene_files/scene_files.h"

namespace wavebake {

// spec is one of
//   builtin:NAME      a scene generated in code (core/scene/builtin_scenes.h)
//   PATH.json         a scene file: meshes + transforms + albedo + camera
//                     (format in storage/scene_files/scene_loader_json.cc)
//   PATH              any mesh file assimp reads (OBJ, PLY, glTF, ...): all of
//                     its meshes, transforms baked in, albedo from the
//                     material's diffuse colour; no camera (see FramingCamera)
// Every result has passed CheckAndRepairScene; `report` (may be null) says
// what it repaired and which file references `files` warned about. Errors are
// InvalidArgument and name the file and field. Every file read besides the
// spec's own goes through `files` (storage/scene_files/scene_files.h; null: the local
// user's LocalSceneFiles). The content hash of the result is SceneHash
// (core/scene/scene_hash.h).
absl::StatusOr<Scene> LoadScene(std::string_view spec, SceneReport* report = nullptr,
                                const SceneFiles* files = nullptr);

// The meshes[i].file strings of a JSON scene file, as written (what a client
// uploads with the scene, storage/scene_files/scene_bundle.h). Errors as LoadScene's,
// naming the file as `files` does (null: LocalSceneFiles).
absl::StatusOr<std::vector<std::string>> JsonSceneMeshFiles(const std::filesystem::path& path,
                                                            const SceneFiles* files = nullptr);

}  // namespace wavebake
