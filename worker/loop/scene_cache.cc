#include "worker/loop/scene_cache.h"

#include <unistd.h>

#include <atomic>
#include <system_error>
#include <thread>

#include "absl/strings/str_cat.h"
#include "storage/files/sha256.h"
#include "storage/scene_files/scene_bundle.h"
#include "storage/store/store_scene.h"

namespace wavebake {
namespace {

bool IsHexSha256(const std::string& s) {
  return s.size() == 64 && s.find_first_not_of("0123456789abcdef") == std::string::npos;
}

// The bytes must be what their name says: a scene is loaded, and its hash
// recorded in the store, on the strength of that name.
absl::Status CheckHash(const std::filesystem::path& file, const std::string& sha256) {
  absl::StatusOr<std::string> got = Sha256OfFile(file);
  if (!got.ok()) return got.status();
  if (*got == sha256) return absl::OkStatus();
  return absl::DataLossError(
      absl::StrCat("FetchScene: scene ", sha256, ": the fetched bytes hash to ", *got));
}

}  // namespace

std::string CachedSceneName(const v1::SceneRef& ref) {
  std::string name = std::filesystem::path(ref.file_name()).filename().string();
  if (name.empty() || name.front() == '.') name = "scene";
  return name;
}

SceneCache::SceneCache(std::filesystem::path dir, std::map<std::string, std::string> local)
    : dir_(std::move(dir)), local_(std::move(local)) {}

absl::StatusOr<SceneSpec> SceneCache::Resolve(const v1::SceneSource& source, const FetchFn& fetch) {
  if (source.has_builtin()) {
    std::string name = source.builtin();
    if (!name.starts_with("builtin:")) name = "builtin:" + name;
    return SceneSpec{name, name, nullptr};
  }
  if (!source.has_uploaded()) return absl::InvalidArgumentError("scene: the task names no scene");
  const v1::SceneRef& ref = source.uploaded();
  if (!IsHexSha256(ref.sha256()))
    return absl::InvalidArgumentError("scene.uploaded.sha256: not 64 lowercase hex digits");
  // Recorded by its file name, as an uploaded scene is: the store is the
  // same wherever the file was baked from (storage/store/store_scene.h).
  if (auto it = local_.find(ref.sha256()); it != local_.end())
    return SceneSpec{it->second, RecordedSceneName(it->second), nullptr};
  absl::StatusOr<std::filesystem::path> path = Cached(ref, fetch);
  if (!path.ok()) return path.status();
  const bool json = std::filesystem::path(CachedSceneName(ref)).extension() == ".json";
  if (ref.files().empty() && !json)
    return SceneSpec{path->string(), CachedSceneName(ref), ConfinedSceneFiles(path->parent_path())};
  // Its files, each fetched by its own hash, in a directory of their own
  // (storage/scene_files/scene_bundle.h): the scene's references find only them.
  std::vector<BundleFile> files;
  std::vector<std::pair<std::string, std::string>> keyed;
  for (const v1::SceneFileRef& f : ref.files()) {
    if (absl::Status s = CheckBundlePath(f.path(), "scene.uploaded.files.path"); !s.ok()) return s;
    v1::SceneRef file;
    file.set_sha256(f.sha256());
    file.set_size(f.size());
    file.set_file_name(std::filesystem::path(f.path()).filename().string());
    if (!IsHexSha256(file.sha256()))
      return absl::InvalidArgumentError("scene.uploaded.files.sha256: not 64 lowercase hex digits");
    absl::StatusOr<std::filesystem::path> blob = Cached(file, fetch);
    if (!blob.ok()) return blob.status();
    files.push_back({f.path(), *blob});
    keyed.emplace_back(f.path(), f.sha256());
  }
  const std::string key = BundleKey(ref.sha256(), keyed);
  absl::StatusOr<std::filesystem::path> scene =
      MaterializeBundle(dir_ / "bundles", key, CachedSceneName(ref), *path, files);
  if (!scene.ok()) return scene.status();
  if (json) {  // the coordinator refused such a scene already; a worker checks too
    if (absl::Status s = CheckJsonSceneInBundle(*scene, files); !s.ok()) return s;
  }
  return SceneSpec{scene->string(), CachedSceneName(ref), ConfinedSceneFiles(scene->parent_path())};
}

absl::StatusOr<std::filesystem::path> SceneCache::Cached(const v1::SceneRef& ref,
                                                         const FetchFn& fetch) {
  const std::filesystem::path dir = dir_ / ref.sha256();
  const std::filesystem::path path = dir / CachedSceneName(ref);
  std::lock_guard lock(mu_);
  std::error_code ec;
  // Files only ever appear whole and verified (rename below), so one that is
  // there is good unless another writer left a file of the wrong size.
  if (std::filesystem::is_regular_file(path, ec)) {
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec && (ref.size() <= 0 || static_cast<int64_t>(size) == ref.size())) return path;
  }
  std::filesystem::create_directories(dir, ec);
  if (ec)
    return absl::InternalError(absl::StrCat("scene cache ", dir.string(), ": ", ec.message()));
  static std::atomic<uint64_t> counter{0};
  const std::filesystem::path temp =
      dir / absl::StrCat(".fetch-", ::getpid(), "-", counter++, ".tmp");
  absl::Status fetched = fetch(ref, temp);
  if (fetched.ok()) fetched = CheckHash(temp, ref.sha256());
  if (fetched.ok()) {
    std::filesystem::rename(temp, path, ec);
    if (ec)
      fetched =
          absl::InternalError(absl::StrCat("scene cache ", path.string(), ": ", ec.message()));
  }
  std::filesystem::remove(temp, ec);
  if (!fetched.ok()) return fetched;
  return path;
}

}  // namespace wavebake
