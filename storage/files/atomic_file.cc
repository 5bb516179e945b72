#include "storage/files/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <random>
#include <system_error>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace wavebake {
namespace {

// Closes a file descriptor when it goes out of scope.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  // Gives up ownership without closing.
  void Release() { fd_ = -1; }
  // Closes now so that a close() failure (e.g. a deferred NFS write error) is reported.
  int Close() {
    const int rc = ::close(fd_);
    fd_ = -1;
    return rc;
  }

 private:
  int fd_;
};

absl::Status ErrnoError(absl::string_view what, const std::filesystem::path& path, int err) {
  // std::error_code's message is thread-safe, unlike strerror.
  std::string msg = absl::StrCat(what, " ", path.string(), ": ",
                                 std::error_code(err, std::generic_category()).message());
  if (err == ENOENT) return absl::NotFoundError(msg);
  // A full disk or quota: no retry on this filesystem helps (the bake ends).
  if (err == ENOSPC || err == EDQUOT) return absl::ResourceExhaustedError(msg);
  return absl::InternalError(msg);
}

// Temp name for `path`, unique among all writers: the pid separates processes
// on one host (forked workers would share a seeded generator's state), fresh
// OS randomness separates hosts sharing the store (DESIGN.md §4) and threads.
std::filesystem::path TempName(const std::filesystem::path& dir,
                               const std::filesystem::path& path) {
  std::random_device random;
  const uint64_t r = (uint64_t{random()} << 32) | random();
  return dir / absl::StrFormat(".%s.%d.%016x.partial", path.filename().string(), ::getpid(), r);
}

}  // namespace

// The names TempName makes: ".NAME.PID.<16 hex>.partial".
bool IsAtomicTempName(std::string_view full) {
  const absl::string_view name(full.data(), full.size());  // Debian's absl has its own
  constexpr absl::string_view kSuffix = ".partial";
  if (name.size() < 1 + 1 + 17 + kSuffix.size() || name[0] != '.' || !absl::EndsWith(name, kSuffix))
    return false;
  const absl::string_view hex = name.substr(name.size() - kSuffix.size() - 16, 16);
  return name[name.size() - kSuffix.size() - 17] == '.' &&
         std::all_of(hex.begin(), hex.end(), [](char c) { return absl::ascii_isxdigit(c); });
}

namespace {

// Errors name the file being written (`path`), not its temporary name.
absl::Status WriteAll(int fd, std::span<const std::byte> data, const std::filesystem::path& path) {
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return ErrnoError("cannot write", path, errno);
    data = data.subspan(static_cast<size_t>(n));
  }
  return absl::OkStatus();
}

// Makes the rename durable. Some filesystems cannot fsync a directory (EINVAL);
// the rename is still atomic there, so that is not an error.
absl::Status SyncDirectory(const std::filesystem::path& dir) {
  Fd fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (fd.get() < 0) return ErrnoError("cannot open directory", dir, errno);
  if (::fsync(fd.get()) != 0 && errno != EINVAL) return ErrnoError("cannot fsync", dir, errno);
  return absl::OkStatus();
}

absl::Status WriteAndClose(Fd& fd, const std::filesystem::path& path, FileParts parts) {
  for (std::span<const std::byte> data : parts)
    if (absl::Status s = WriteAll(fd.get(), data, path); !s.ok()) return s;
  if (::fsync(fd.get()) != 0) return ErrnoError("cannot fsync", path, errno);
  if (fd.Close() != 0) return ErrnoError("cannot close", path, errno);
  return absl::OkStatus();
}

// Creates, fills and syncs a temp file beside `path`; removes it on failure.
absl::StatusOr<std::filesystem::path> WriteTemp(const std::filesystem::path& dir,
                                                const std::filesystem::path& path,
                                                FileParts parts) {
  for (int attempt = 0;; ++attempt) {
    const std::filesystem::path tmp = TempName(dir, path);
    // O_EXCL: never write into (or later remove) another writer's temp file.
    // 0666 & umask like any other file: a store on a shared filesystem is read
    // by other users' processes (mkstemp's 0600 would hide it).
    Fd fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666));
    if (fd.get() < 0 && errno == EEXIST && attempt < 8) continue;
    if (fd.get() < 0) return ErrnoError("cannot create a temp file for", path, errno);
    if (absl::Status s = WriteAndClose(fd, path, parts); !s.ok()) {
      ::unlink(tmp.c_str());  // best effort; the write error is the one to report
      return s;
    }
    return tmp;
  }
}

// Opens `path` for reading only if it is a regular file. O_NONBLOCK makes the
// open itself safe: a plain open of a FIFO blocks until a writer appears (a
// FIFO planted as a chunk or as .zattrs hung `relight` forever), and a
// device such as /dev/zero never ends. fstat then looks at what was opened,
// so nothing can be swapped in between the check and the read. Regular files
// ignore O_NONBLOCK, so the reads that follow behave as without it.
absl::StatusOr<int> OpenRegularForReading(const std::filesystem::path& path, struct stat& st) {
  const int raw = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (raw < 0) return ErrnoError("cannot open", path, errno);
  Fd fd(raw);
  if (::fstat(fd.get(), &st) != 0) return ErrnoError("cannot stat", path, errno);
  if (!S_ISREG(st.st_mode)) {
    const char* kind = S_ISFIFO(st.st_mode)   ? "a FIFO"
                       : S_ISCHR(st.st_mode)  ? "a character device"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                       : S_ISDIR(st.st_mode)  ? "a directory"
                                              : "not a regular file";
    return absl::InternalError(absl::StrCat(path.string(), ": not a regular file (", kind, ")"));
  }
  const int out = fd.get();
  fd.Release();
  return out;
}

// The whole of `path` into `data`, resized to the file's size.
template <class Buffer>
absl::Status ReadWholeFile(const std::filesystem::path& path, Buffer& data) {
  struct stat st {};
  absl::StatusOr<int> opened = OpenRegularForReading(path, st);
  if (!opened.ok()) return opened.status();
  Fd fd(*opened);
  data.resize(static_cast<size_t>(st.st_size));
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::read(fd.get(), data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return ErrnoError("cannot read", path, errno);
    if (n == 0) break;  // the file shrank; report what we read as a short read below
    done += static_cast<size_t>(n);
  }
  if (done != data.size()) {
    return absl::InternalError(
        absl::StrFormat("short read of %s: %d of %d bytes", path.string(), done, data.size()));
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status AtomicWriteFile(const std::filesystem::path& path, std::span<const std::byte> data) {
  return AtomicWriteFileParts(path, FileParts(&data, 1));
}

absl::Status AtomicWriteFileParts(const std::filesystem::path& path, FileParts parts) {
  const std::filesystem::path dir = path.parent_path().empty() ? "." : path.parent_path();
  absl::StatusOr<std::filesystem::path> tmp = WriteTemp(dir, path, parts);
  if (!tmp.ok()) return tmp.status();
  if (::rename(tmp->c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp->c_str());
    return ErrnoError(absl::StrCat("cannot rename ", tmp->string(), " to"), path, err);
  }
  return SyncDirectory(dir);
}

absl::Status CreateDirectories(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return ErrnoError("cannot create directory", dir, ec.value());
  return absl::OkStatus();
}

absl::StatusOr<std::vector<std::byte>> ReadFile(const std::filesystem::path& path) {
  std::vector<std::byte> data;
  if (absl::Status s = ReadWholeFile(path, data); !s.ok()) return s;
  return data;
}

absl::Status ReadFileInto(const std::filesystem::path& path, ByteBuffer& data) {
  return ReadWholeFile(path, data);
}

absl::Status ReadFileRangeInto(const std::filesystem::path& path, uint64_t offset, size_t size,
                               ByteBuffer& data) {
  struct stat st {};
  absl::StatusOr<int> opened = OpenRegularForReading(path, st);
  if (!opened.ok()) return opened.status();
  Fd fd(*opened);
  data.resize(size);
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::pread(fd.get(), data.data() + done, size - done, off_t(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return ErrnoError("cannot read", path, errno);
    if (n == 0) break;  // the file ends first
    done += static_cast<size_t>(n);
  }
  if (done != size) {
    return absl::OutOfRangeError(absl::StrFormat("short read of %s: %d of %d bytes at %d",
                                                 path.string(), done, size, offset));
  }
  return absl::OkStatus();
}

absl::Status AtomicWriteText(const std::filesystem::path& path, std::string_view text) {
  return AtomicWriteFile(path, std::as_bytes(std::span(text)));
}

absl::Status RemoveAbandonedTempFiles(const std::filesystem::path& dir) {
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec) && IsAtomicTempName(it->path().filename().string()))
      std::filesystem::remove(it->path(), ec);
  }
  if (ec) return absl::InternalError(absl::StrCat(dir.string(), ": ", ec.message()));
  return absl::OkStatus();
}

}  // namespace wavebake
