#include "storage/zarr/zarr_group.h"

#include <system_error>

#include "absl/strings/str_cat.h"
#include "storage/files/atomic_file.h"
#include "storage/files/json_file.h"

namespace wavebake {

absl::Status WriteGroup(const std::filesystem::path& dir) {
  if (absl::Status s = CreateDirectories(dir); !s.ok()) return s;
  return WriteJsonFile(dir / ".zgroup", {{"zarr_format", 2}});
}

absl::Status WriteAttrs(const std::filesystem::path& dir, const nlohmann::json& attrs) {
  if (!attrs.is_object()) {
    return absl::InvalidArgumentError(
        absl::StrCat((dir / ".zattrs").string(), ": attributes must be a JSON object"));
  }
  return WriteJsonFile(dir / ".zattrs", attrs);
}

absl::StatusOr<nlohmann::json> ReadAttrs(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    return absl::NotFoundError(absl::StrCat(dir.string(), ": no such group or array"));
  }
  const std::filesystem::path path = dir / ".zattrs";
  absl::StatusOr<nlohmann::json> attrs = ReadJsonFile(path);
  if (absl::IsNotFound(attrs.status())) return nlohmann::json::object();
  if (attrs.ok() && !attrs->is_object()) {
    return absl::InvalidArgumentError(absl::StrCat(path.string(), ": not a JSON object"));
  }
  return attrs;
}

}  // namespace wavebake
