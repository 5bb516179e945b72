#pragma once
// One coordinator per --data: two processes on one SQLite state would each
// keep their own view in memory and overwrite the other's (job ids, event
// sequence numbers). The coordinator holds an exclusive flock(2) on
// <data dir>/.wavebake-coordinator.lock (and the same in its store root) for
// its lifetime; the file holds its pid, which a second coordinator names when
// it refuses to start. The kernel releases
// the lock when the holder exits, however it exits, so a crash leaves no
// stale lock to remove by hand.
#include <filesystem>
#include <string>

#include "absl/status/statusor.h"

namespace wavebake {

class DataDirLock {
 public:
  // FailedPrecondition naming the holder's pid when another process (or
  // another DataDirLock in this one) holds the lock of `dir`; errors start
  // with `field` (the option that named the directory).
  static absl::StatusOr<DataDirLock> Acquire(const std::filesystem::path& dir,
                                             const std::string& field);
  DataDirLock(DataDirLock&& o) noexcept;
  DataDirLock& operator=(DataDirLock&& o) noexcept;
  DataDirLock(const DataDirLock&) = delete;
  DataDirLock& operator=(const DataDirLock&) = delete;
  ~DataDirLock();

  static constexpr const char* kFileName = ".wavebake-coordinator.lock";

 private:
  explicit DataDirLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace wavebake
