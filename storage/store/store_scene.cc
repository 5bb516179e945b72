#include "storage/store/store_scene.h"

#include <cstdlib>
#include <string_view>
#include <system_error>

namespace wavebake {

std::string LocateStoreScene(const std::string& recorded, const std::filesystem::path& store) {
  namespace fs = std::filesystem;
  if (recorded.starts_with("builtin:") || recorded.empty()) return recorded;
  std::error_code ec;
  if (fs::exists(recorded, ec)) return recorded;
  const fs::path name = fs::path(recorded).filename();
  if (name.empty()) return recorded;
  if (fs::path beside = store.parent_path() / name; fs::exists(beside, ec)) return beside.string();
  if (const char* path = std::getenv("WAVEBAKE_SCENE_PATH")) {
    std::string_view dirs(path);
    while (!dirs.empty()) {
      const size_t colon = dirs.find(':');
      const std::string_view dir = dirs.substr(0, colon);
      dirs = colon == std::string_view::npos ? std::string_view() : dirs.substr(colon + 1);
      if (dir.empty()) continue;
      if (fs::path there = fs::path(dir) / name; fs::exists(there, ec)) return there.string();
    }
  }
  return recorded;
}

std::string RecordedSceneName(const std::string& spec) {
  if (spec.starts_with("builtin:")) return spec;
  std::string name = std::filesystem::path(spec).filename().string();
  return name.empty() ? spec : name;
}

}  // namespace wavebake
