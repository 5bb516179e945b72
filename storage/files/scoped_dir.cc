#include "storage/files/scoped_dir.h"

#include <stdlib.h>

#include <string>
#include <system_error>

#include "absl/strings/str_cat.h"

namespace wavebake {

absl::StatusOr<ScopedDir> ScopedDir::CreateBeside(const std::filesystem::path& out,
                                                  std::string_view tag) {
  const std::filesystem::path parent = std::filesystem::absolute(out).parent_path();
  std::string pattern =
      (parent / absl::StrCat(".", out.filename().string(), ".", std::string(tag), "-XXXXXX"))
          .string();
  if (::mkdtemp(pattern.data()) == nullptr)
    return absl::InvalidArgumentError(
        absl::StrCat("out: cannot create a directory in ", parent.string()));
  return ScopedDir(pattern);
}

ScopedDir::~ScopedDir() {
  if (path_.empty()) return;
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace wavebake
