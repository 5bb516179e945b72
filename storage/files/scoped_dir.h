#pragma once
// A directory owned by a scope: removed with everything in it when the
// object goes (DESIGN.md §5: a failed or interrupted command leaves nothing
// behind). Bakes create their work directories beside the output, on the
// same filesystem, so what they publish moves there by rename.
#include <filesystem>
#include <string_view>

#include "absl/status/statusor.h"

namespace wavebake {

class ScopedDir {
 public:
  // Adopts `path` (which may not exist yet).
  explicit ScopedDir(std::filesystem::path path) : path_(std::move(path)) {}
  // Creates ".<out's file name>.<tag>-XXXXXX" in out's parent directory; an
  // error names the `out` field.
  static absl::StatusOr<ScopedDir> CreateBeside(const std::filesystem::path& out,
                                                std::string_view tag);

  ScopedDir(ScopedDir&& other) noexcept : path_(std::move(other.path_)) { other.path_.clear(); }
  ScopedDir& operator=(ScopedDir&&) = delete;
  ScopedDir(const ScopedDir&) = delete;
  ScopedDir& operator=(const ScopedDir&) = delete;
  ~ScopedDir();

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;  // empty once moved from
};

}  // namespace wavebake
