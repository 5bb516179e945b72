#pragma once
// A scene file uploaded with the files it references (a JSON scene's meshes,
// an OBJ's material library), each stored by its own content hash (DESIGN.md
// §4 UploadScene). To load it, the coordinator and every worker build a
// directory that holds exactly those files at their relative paths, linked
// to the blobs they have, and load the scene from there: a relative mesh
// path then finds the uploaded bytes and nothing else of the host's disk.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace wavebake {

struct BundleFile {
  std::string path;            // relative to the scene file, '/'-separated
  std::filesystem::path blob;  // where this host has the bytes
};

// The name of a bundle's contents: SHA-256 over the scene's hash and every
// (path, hash) pair in path order.
std::string BundleKey(const std::string& scene_sha256,
                      std::vector<std::pair<std::string, std::string>> path_sha256);

// A path a bundle may hold: relative, '/'-separated, no empty, "." or ".."
// component, no backslash. InvalidArgument "FIELD: ..." otherwise.
absl::Status CheckBundlePath(const std::string& path, const std::string& field);

// <root>/<key>/<scene_name> and <root>/<key>/<file.path> for every file,
// symbolic links to their blobs; `key` names the contents (so equal bundles
// share a directory and different ones never do). Built beside the final
// name and renamed into place: concurrent builders of one bundle agree.
// Returns the scene file's path inside it.
absl::StatusOr<std::filesystem::path> MaterializeBundle(const std::filesystem::path& root,
                                                        const std::string& key,
                                                        const std::string& scene_name,
                                                        const std::filesystem::path& scene_blob,
                                                        const std::vector<BundleFile>& files);

// Every meshes[i].file of the JSON scene at `scene` names a file of the
// bundle (exactly, as listed): InvalidArgument "meshes[i].file: ..." naming
// the path otherwise, so a scene loads only what was uploaded with it.
absl::Status CheckJsonSceneInBundle(const std::filesystem::path& scene,
                                    const std::vector<BundleFile>& files);

}  // namespace wavebake
