#include "storage/store/store_check.h"

#include <algorithm>
#include <cctype>
#include <string>
#include <system_error>

#include "absl/status/statusor.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"

namespace wavebake {
namespace {

namespace fs = std::filesystem;

// "0", "12.3": a Zarr v2 chunk key.
bool IsChunkKey(const std::string& name) {
  if (name.empty() || name.front() == '.' || name.back() == '.') return false;
  bool dot = false;
  for (char c : name) {
    if (c == '.') {
      if (dot) return false;
      dot = true;
    } else if (!std::isdigit(static_cast<unsigned char>(c))) {
      return false;
    } else {
      dot = false;
    }
  }
  return true;
}

bool IsTemporary(const std::string& name) {
  return name.size() > 9 && name.front() == '.' && name.ends_with(".partial");
}

// staging/groups and staging/finalize: "<n><suffix>" files (".wbg", ".wbq"),
// `also` (staging/finalize's plan.wbp) and their temporaries, nothing else.
std::optional<fs::path> ForeignInNumbered(const fs::path& dir, const std::string& suffix,
                                          const std::string& also = "") {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    const bool numbered =
        name.ends_with(suffix) && IsChunkKey(name.substr(0, name.size() - suffix.size()));
    const bool known = numbered || (!also.empty() && name == also) || IsTemporary(name);
    if (e.is_symlink(ec) || !e.is_regular_file(ec) || !known) return e.path();
  }
  if (ec) return dir;
  return std::nullopt;
}

std::optional<fs::path> ForeignIn(const fs::path& store, const fs::path& dir) {
  std::error_code ec;
  if (dir == store / store::kStagingGroups) return ForeignInNumbered(dir, ".wbg");
  if (dir == store / store::kStagingFinalize) return ForeignInNumbered(dir, ".wbq", "plan.wbp");
  const bool array = fs::exists(dir / ".zarray", ec);
  if (!array && !fs::exists(dir / ".zgroup", ec)) return dir;  // no Zarr node
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_symlink(ec)) return e.path();
    if (e.is_directory(ec)) {
      if (array) return e.path();  // arrays hold no directories
      if (std::optional<fs::path> f = ForeignIn(store, e.path())) return f;
      continue;
    }
    if (name == ".zattrs" || name == (array ? ".zarray" : ".zgroup") || IsTemporary(name)) continue;
    if (array && IsChunkKey(name)) continue;
    return e.path();
  }
  if (ec) return dir;
  return std::nullopt;
}

}  // namespace

// The readers open every final array complete (ZarrArray::OpenComplete) and
// hold it to the manifest; reading them all is the check.
absl::Status CheckStoreComplete(const std::filesystem::path& store) {
  if (absl::StatusOr<SampleSet> samples = ReadSamples(store); !samples.ok())
    return samples.status();
  return ReadTransport(store).status();
}

std::optional<std::filesystem::path> ForeignStoreEntry(const std::filesystem::path& store) {
  return ForeignIn(store, store);
}

}  // namespace wavebake
