#include "worker/columns/publish_store.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "absl/strings/str_cat.h"
#include "storage/store/store_check.h"
#include "storage/store/store_reader.h"

namespace wavebake {
namespace {

absl::Status Errno(const std::string& what) {
  return absl::InternalError(absl::StrCat(what, ": ", std::strerror(errno)));
}

}  // namespace

absl::Status CheckOutputPath(const std::filesystem::path& out) {
  std::error_code ec;
  const std::filesystem::path parent = std::filesystem::absolute(out).parent_path();
  if (!std::filesystem::is_directory(parent, ec))
    return absl::InvalidArgumentError(
        absl::StrCat("out: directory ", parent.string(), " does not exist"));
  const std::filesystem::file_status status = std::filesystem::symlink_status(out, ec);
  if (!std::filesystem::exists(status)) return absl::OkStatus();
  if (std::filesystem::is_symlink(status))
    return absl::InvalidArgumentError(absl::StrCat(
        "out: ", out.string(), " is a symbolic link; give the store's own path (its target)"));
  if (!std::filesystem::is_directory(out, ec) || !ReadStoreInfo(out).ok())
    return absl::AlreadyExistsError(absl::StrCat(
        "out: ", out.string(), " exists and is not a wavebake store; refusing to overwrite it"));
  if (std::optional<std::filesystem::path> foreign = ForeignStoreEntry(out))
    return absl::AlreadyExistsError(absl::StrCat(
        "out: the store ", out.string(), " holds ", foreign->string(),
        ", which no bake writes; refusing to replace the store (it would be deleted): move it "
        "out first"));
  return absl::OkStatus();
}

absl::StatusOr<std::filesystem::path> ResolveOutputPath(const std::filesystem::path& out) {
  std::filesystem::path path = out;
  std::error_code ec;
  for (int hops = 0; std::filesystem::is_symlink(path, ec); ++hops) {
    if (hops == 40)
      return absl::InvalidArgumentError(
          absl::StrCat("out: ", out.string(), ": too many levels of symbolic links"));
    const std::filesystem::path target = std::filesystem::read_symlink(path, ec);
    if (ec)
      return absl::InvalidArgumentError(absl::StrCat("out: ", out.string(), ": ", ec.message()));
    path = target.is_absolute() ? target : path.parent_path() / target;
  }
  if (absl::Status s = CheckOutputPath(path); !s.ok()) return s;
  return path;
}

absl::Status PublishStore(const std::filesystem::path& partial, const std::filesystem::path& out) {
  if (::rename(partial.c_str(), out.c_str()) == 0) return absl::OkStatus();
  // rename(2) onto a non-empty directory fails: an old store is there.
  if (errno != ENOTEMPTY && errno != EEXIST)
    return Errno(absl::StrCat("rename ", partial.string(), " -> ", out.string()));
  if (absl::Status s = CheckOutputPath(out); !s.ok()) return s;
  std::error_code ec;
  if (::renameat2(AT_FDCWD, partial.c_str(), AT_FDCWD, out.c_str(), RENAME_EXCHANGE) == 0) {
    std::filesystem::remove_all(partial, ec);  // now the old store
    return absl::OkStatus();
  }
  if (errno != EINVAL && errno != ENOSYS)
    return Errno(absl::StrCat("exchange ", partial.string(), " <-> ", out.string()));
  // No exchange on this filesystem: a short window without `out`, never a mix.
  const std::filesystem::path old = out.string() + absl::StrCat(".old-", ::getpid());
  if (::rename(out.c_str(), old.c_str()) != 0) return Errno(absl::StrCat("rename ", out.string()));
  if (::rename(partial.c_str(), out.c_str()) != 0) {
    const absl::Status s = Errno(absl::StrCat("rename ", partial.string()));
    ::rename(old.c_str(), out.c_str());
    return s;
  }
  std::filesystem::remove_all(old, ec);
  return absl::OkStatus();
}

}  // namespace wavebake
