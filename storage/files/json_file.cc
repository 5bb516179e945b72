#include "storage/files/json_file.h"

#include <string>

#include "absl/strings/str_cat.h"
#include "storage/files/atomic_file.h"

namespace wavebake {

absl::Status WriteJsonFile(const std::filesystem::path& path, const nlohmann::json& value) {
  std::string text;
  try {
    // ASCII only (\uXXXX escapes): Debian's zarr 2 decodes .zattrs as ASCII
    // and cannot open the attributes of a file holding a "×".
    text = value.dump(4, ' ', /*ensure_ascii=*/true) + "\n";
  } catch (const nlohmann::json::exception& e) {  // e.g. invalid UTF-8 in a string
    return absl::InvalidArgumentError(absl::StrCat("cannot write ", path.string(), ": ", e.what()));
  }
  return AtomicWriteText(path, text);
}

absl::StatusOr<nlohmann::json> ReadJsonFile(const std::filesystem::path& path) {
  absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(path);
  if (!bytes.ok()) return bytes.status();
  const auto* begin = reinterpret_cast<const char*>(bytes->data());
  nlohmann::json value = nlohmann::json::parse(begin, begin + bytes->size(), nullptr,
                                               /*allow_exceptions=*/false);
  if (value.is_discarded()) {
    return absl::InvalidArgumentError(absl::StrCat(path.string(), ": not valid JSON"));
  }
  return value;
}

}  // namespace wavebake
