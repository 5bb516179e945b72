#pragma once
// The two file readers behind LoadScene. Neither runs CheckAndRepairScene;
// LoadScene does, once, for every kind of scene.
#include <filesystem>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene.h"

namespace wavebake {

// Every triangle mesh of a file assimp reads, in world space; normals only if
// the file has them. Errors name the path.
absl::StatusOr<std::vector<Mesh>> ReadMeshFile(const std::filesystem::path& path);

// A JSON scene file; mesh paths relative to the JSON file's directory.
absl::StatusOr<Scene> ReadJsonScene(const std::filesystem::path& path);

}  // namespace wavebake
