#include "runtime/atomic_write.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "absl/strings/str_cat.h"

namespace wavebake {

namespace {

absl::Status ErrnoError(const std::string& what, const std::filesystem::path& path) {
  const int err = errno;
  return absl::Status(absl::ErrnoToStatusCode(err),
                      absl::StrCat(path.string(), ": ", what, ": ", std::strerror(err)));
}

// Unique per process and call, so concurrent writers never share a temp file.
std::filesystem::path TempPathFor(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path tmp = path;
  tmp += absl::StrCat(".tmp.", ::getpid(), ".", counter++);
  return tmp;
}

absl::Status WriteAll(int fd, std::span<const std::byte> bytes, const std::filesystem::path& tmp) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return ErrnoError("write", tmp);
    bytes = bytes.subspan(static_cast<size_t>(n));
  }
  if (::fsync(fd) != 0) return ErrnoError("fsync", tmp);
  return absl::OkStatus();
}

}  // namespace

absl::Status WriteFileAtomically(const std::filesystem::path& path,
                                 std::span<const std::byte> bytes) {
  const std::filesystem::path tmp = TempPathFor(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return ErrnoError("cannot create", tmp);
  absl::Status status = WriteAll(fd, bytes, tmp);
  if (::close(fd) != 0 && status.ok()) status = ErrnoError("close", tmp);
  if (status.ok() && ::rename(tmp.c_str(), path.c_str()) != 0) {
    status = ErrnoError("cannot rename temporary file onto", path);
  }
  if (!status.ok()) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
  }
  return status;
}

}  // namespace wavebake
