#pragma once
// The two file readers behind LoadScene. Neither runs CheckAndRepairScene;
// LoadScene does, once, for every kind of scene.
#include <filesystem>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "storage/scene_files/scene_files.h"

namespace wavebake {

// Every triangle mesh of a file assimp reads, in world space; normals only if
// the file has them. Every file assimp opens (the mesh, an OBJ's materials)
// goes through `files`. Errors name the path as files.Name does.
absl::StatusOr<std::vector<Mesh>> ReadMeshFile(const std::filesystem::path& path,
                                               const SceneFiles& files);

// A JSON scene file; mesh references resolved by `files` (relative to the
// JSON file's directory). `warnings` gets one line per reference `files`
// warns about, naming the file and field.
absl::StatusOr<Scene> ReadJsonScene(const std::filesystem::path& path, const SceneFiles& files,
                                    std::vector<std::string>& warnings);

}  // namespace wavebake
