#pragma once
// Where a worker finds the scene of a task (DESIGN.md §4: "Workers fetch
// scenes by content hash from the coordinator and cache them"). A built-in is
// generated in code; an uploaded scene is fetched once into the cache
// directory as <dir>/<sha256>/<file name> (the loaders pick the format by
// extension) and reused by every later task and job, and by other worker
// processes sharing the directory (files appear by rename, whole).
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "storage/scene_files/scene_files.h"
#include "wavebake.pb.h"

namespace wavebake {

struct SceneSpec {
  std::string load;      // what LoadScene reads on this machine
  std::string recorded;  // what the store records as its scene (the same on every worker)
  // What else LoadScene may read: an uploaded scene only what was uploaded
  // with it (storage/scene_files/scene_files.h); null for built-ins and local scenes.
  std::shared_ptr<const SceneFiles> files;
};

class SceneCache {
 public:
  // Streams the scene `ref` into the file `dest` (which it creates).
  using FetchFn =
      std::function<absl::Status(const v1::SceneRef& ref, const std::filesystem::path& dest)>;

  // local: uploaded scenes this process can read where they came from,
  // sha256 → LoadScene spec (the embedded bake); they are neither fetched nor
  // copied, and the store records their file name, as for any upload.
  SceneCache(std::filesystem::path dir, std::map<std::string, std::string> local = {});

  // builtin:NAME stays itself. An uploaded scene loads from the cache (fetched
  // on first use) and is recorded by its uploaded file name.
  absl::StatusOr<SceneSpec> Resolve(const v1::SceneSource& source, const FetchFn& fetch);

  const std::filesystem::path& dir() const { return dir_; }

 private:
  absl::StatusOr<std::filesystem::path> Cached(const v1::SceneRef& ref, const FetchFn& fetch);

  std::filesystem::path dir_;
  std::map<std::string, std::string> local_;
  std::mutex mu_;  // one fetch at a time: they are rare, and two of one scene are waste
};

// The file name an uploaded scene is cached and recorded under: the last
// component of ref.file_name, "scene" if that is empty or a dot name.
std::string CachedSceneName(const v1::SceneRef& ref);

}  // namespace wavebake
