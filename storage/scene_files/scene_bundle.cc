#include "storage/scene_files/scene_bundle.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <set>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "storage/files/sha256.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake {

std::string BundleKey(const std::string& scene_sha256,
                      std::vector<std::pair<std::string, std::string>> path_sha256) {
  std::sort(path_sha256.begin(), path_sha256.end());
  Sha256 sha;
  sha.Update(scene_sha256);
  for (const auto& [path, hash] : path_sha256) sha.Update(absl::StrCat("\n", path, "\0", hash));
  return sha.HexDigest();
}

absl::Status CheckBundlePath(const std::string& path, const std::string& field) {
  const auto bad = [&](absl::string_view why) {
    return absl::InvalidArgumentError(absl::StrCat(field, ": '", path, "' ", why));
  };
  if (path.empty()) return bad("is empty");
  if (path.front() == '/') return bad("is absolute (paths are relative to the scene file)");
  if (path.find('\\') != std::string::npos) return bad("has a backslash (use '/')");
  if (path.size() > 1024) return bad("is longer than 1024 bytes");
  for (size_t start = 0; start <= path.size();) {
    const size_t end = std::min(path.find('/', start), path.size());
    const absl::string_view part(path.data() + start, end - start);
    if (part == "..") return bad("leaves the scene's directory ('..')");
    if (part.empty() || part == ".") return bad("has an empty or '.' component");
    start = end + 1;
  }
  return absl::OkStatus();
}

absl::StatusOr<std::filesystem::path> MaterializeBundle(const std::filesystem::path& root,
                                                        const std::string& key,
                                                        const std::string& scene_name,
                                                        const std::filesystem::path& scene_blob,
                                                        const std::vector<BundleFile>& files) {
  const std::filesystem::path dir = root / key;
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec)) return dir / scene_name;
  static std::atomic<uint64_t> counter{0};
  const std::filesystem::path temp =
      root / absl::StrCat(".", key, ".", ::getpid(), "-", counter++, ".tmp");
  const auto fail = [&](const std::filesystem::path& p, const std::error_code& e) {
    std::error_code ignored;
    std::filesystem::remove_all(temp, ignored);
    return absl::InternalError(absl::StrCat("scene bundle ", p.string(), ": ", e.message()));
  };
  std::filesystem::create_directories(temp, ec);
  if (ec) return fail(temp, ec);
  std::vector<BundleFile> all = files;
  all.push_back({scene_name, scene_blob});
  for (const BundleFile& f : all) {
    const std::filesystem::path link = temp / f.path;
    std::filesystem::create_directories(link.parent_path(), ec);
    if (!ec) std::filesystem::create_symlink(std::filesystem::absolute(f.blob), link, ec);
    if (ec) return fail(link, ec);
  }
  std::filesystem::rename(temp, dir, ec);
  if (ec) {  // another builder of the same bundle got there first
    std::error_code ignored;
    std::filesystem::remove_all(temp, ignored);
    if (!std::filesystem::is_directory(dir, ignored)) return fail(dir, ec);
  }
  return dir / scene_name;
}

absl::Status CheckJsonSceneInBundle(const std::filesystem::path& scene,
                                    const std::vector<BundleFile>& files) {
  // Named relative to the bundle: the client sees no server path.
  const std::unique_ptr<SceneFiles> bundle = ConfinedSceneFiles(scene.parent_path());
  absl::StatusOr<std::vector<std::string>> meshes = JsonSceneMeshFiles(scene, bundle.get());
  if (!meshes.ok()) return meshes.status();
  std::set<std::string> listed;
  for (const BundleFile& f : files) listed.insert(f.path);
  for (size_t i = 0; i < meshes->size(); ++i) {
    const std::string field = absl::StrCat("meshes[", i, "].file");
    if (absl::Status s = CheckBundlePath((*meshes)[i], field); !s.ok()) return s;
    if (!listed.contains((*meshes)[i])) {
      return absl::InvalidArgumentError(absl::StrCat(
          field, ": '", (*meshes)[i], "' is not among the files uploaded with the scene"));
    }
  }
  return absl::OkStatus();
}

}  // namespace wavebake
