#include "worker/publish_store.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "absl/strings/str_cat.h"
#include "storage/store_reader.h"

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
  if (!std::filesystem::exists(std::filesystem::symlink_status(out, ec))) return absl::OkStatus();
  if (std::filesystem::is_directory(out, ec) && ReadStoreInfo(out).ok()) return absl::OkStatus();
  return absl::AlreadyExistsError(absl::StrCat(
      "out: ", out.string(), " exists and is not a wavebake store; refusing to overwrite it"));
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
