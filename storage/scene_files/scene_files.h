#pragma once
// Which files a scene file may make the loader read besides itself: a JSON
// scene's meshes[i].file, an OBJ's mtllib, a glTF's buffers. LoadScene asks a
// SceneFiles for every one of them, so what a scene can reach is decided in
// one place:
//
//   LocalSceneFiles     the user's own bake: anything the process can read.
//                       An absolute reference or one with ".." is allowed but
//                       warned about (a remote job would refuse it).
//   ConfinedSceneFiles  an uploaded scene (coordinator, worker): only files
//                       under one directory the server itself laid out — the
//                       upload and whatever was uploaded with it. Absolute
//                       references and ".." are INVALID_ARGUMENT, and
//                       messages name files relative to that directory, so no
//                       server path reaches a client.
//
// A bundle of uploaded files plugs in by laying its files out under the
// confined root by their relative names (copies, or links the server makes
// to content-hashed blobs), or by another SceneFiles that maps names to blobs.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"

namespace wavebake {

class SceneFiles {
 public:
  virtual ~SceneFiles() = default;

  // A reference written in the scene file `from` (relative to from's
  // directory) → the path to read. Errors are InvalidArgument saying why,
  // naming the reference as written; `warning` is set (else left alone) for
  // a reference allowed here that an uploaded scene could not make.
  virtual absl::StatusOr<std::filesystem::path> Resolve(const std::filesystem::path& from,
                                                        std::string_view reference,
                                                        std::string* warning) const = 0;

  // A path a mesh reader composed itself (assimp's IOSystem: the scene file,
  // an OBJ's mtllib) → the path to open, or nullopt: refused, treated as absent.
  virtual std::optional<std::filesystem::path> Open(const std::filesystem::path& path) const = 0;

  // How messages name a path ("scene file 'x'"); free text from a reader
  // (assimp's error strings) goes through Scrub before it is quoted.
  virtual std::string Name(const std::filesystem::path& path) const = 0;
  virtual std::string Scrub(std::string message) const = 0;
};

std::unique_ptr<SceneFiles> LocalSceneFiles();
// root: a directory (created by the server) that holds the scene file.
std::unique_ptr<SceneFiles> ConfinedSceneFiles(std::filesystem::path root);

// The lexical rule of uploaded scenes: a non-empty relative path with no ".."
// (and no root name). Empty string when fine, else why not (for messages).
std::string UnsafeReference(std::string_view reference);

}  // namespace wavebake
