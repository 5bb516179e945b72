#include "coordinator/state/orphan_stores.h"

#include <spdlog/spdlog.h>

#include <system_error>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "proto/bake_request.h"

namespace wavebake {

absl::StatusOr<int> RemoveOrphanPartialStores(const std::filesystem::path& store_root,
                                              const std::set<std::string>& live) {
  std::set<std::string> keep;
  for (const std::string& store_path : live) keep.insert(PartialStorePath(store_path));
  std::vector<std::filesystem::path> orphans;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(store_root, ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    // ".NAME.partial" with NAME an output name (never starting with '.'); a
    // temp file of AtomicWriteFile has the same shape but is no directory.
    constexpr absl::string_view kSuffix = ".partial";
    if (name.size() <= 1 + kSuffix.size() || name[0] != '.' || name[1] == '.' ||
        !absl::EndsWith(name, kSuffix) || keep.contains(name))
      continue;
    std::error_code type_ec;
    if (it->is_directory(type_ec) && !it->is_symlink(type_ec)) orphans.push_back(it->path());
  }
  if (ec) return absl::InternalError(absl::StrCat("store root: ", ec.message()));
  for (const std::filesystem::path& dir : orphans) {
    std::filesystem::remove_all(dir, ec);
    if (ec) {
      return absl::InternalError(
          absl::StrCat("store root: cannot remove ", dir.string(), ": ", ec.message()));
    }
    spdlog::info("coordinator: removed {}, the partial store of no unfinished job", dir.string());
  }
  return static_cast<int>(orphans.size());
}

}  // namespace wavebake
