#include "coordinator/state/data_dir_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>
#include <utility>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

std::string ErrnoText(int err) { return std::error_code(err, std::generic_category()).message(); }

// The holder's pid as it wrote it; "unknown" while it has not yet.
std::string HolderPid(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof(buf) - 1, 0);
  std::string pid(absl::StripAsciiWhitespace(std::string(buf, n > 0 ? size_t(n) : 0)));
  return pid.empty() ? "unknown" : pid;
}

}  // namespace

absl::StatusOr<DataDirLock> DataDirLock::Acquire(const std::filesystem::path& dir,
                                                 const std::string& field) {
  const std::filesystem::path path = dir / kFileName;
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(field, ": cannot open ", path.string(), ": ", ErrnoText(errno)));
  }
  DataDirLock lock(fd);
  // flock, not fcntl: its lock belongs to the open file, so a second
  // coordinator in the same process (a test, an embedding) is refused too.
  int rc;
  do rc = ::flock(fd, LOCK_EX | LOCK_NB);
  while (rc != 0 && errno == EINTR);
  if (rc != 0) {
    const int err = errno;
    if (err == EWOULDBLOCK) {
      return absl::FailedPreconditionError(
          absl::StrCat(field, ": ", dir.string(), " is in use by another coordinator (pid ",
                       HolderPid(fd), ", holding ", path.string(), ")"));
    }
    return absl::InternalError(
        absl::StrCat(field, ": cannot lock ", path.string(), ": ", ErrnoText(err)));
  }
  // Best effort: on a full disk the lock still holds, only the pid is missing
  // from the refusal ("unknown"); a full disk is no reason not to start.
  const std::string pid = absl::StrCat(::getpid(), "\n");
  if (::ftruncate(fd, 0) == 0) (void)!::pwrite(fd, pid.data(), pid.size(), 0);
  return lock;
}

DataDirLock::DataDirLock(DataDirLock&& o) noexcept : fd_(std::exchange(o.fd_, -1)) {}

DataDirLock& DataDirLock::operator=(DataDirLock&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(o.fd_, -1);
  }
  return *this;
}

// Closing the file releases the lock; the file stays (removing it would race
// with a coordinator that just opened it).
DataDirLock::~DataDirLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace wavebake
