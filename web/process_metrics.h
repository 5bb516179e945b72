#pragma once
// The process_* metrics every Prometheus client library exports
// (prometheus.io, "Writing client libraries": standard and runtime
// collectors), read from Linux's /proc for this process: CPU time, resident
// memory, open and allowed file descriptors, and the start time.
#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace wavebake::web {

struct ProcessStats {
  double cpu_seconds = 0;         // user + system (proc(5): /proc/pid/stat utime, stime)
  int64_t resident_bytes = 0;     // rss pages × page size
  int64_t virtual_bytes = 0;      // vsize
  int64_t open_fds = 0;           // entries of /proc/self/fd
  int64_t max_fds = 0;            // RLIMIT_NOFILE's soft limit
  double start_time_seconds = 0;  // since the Unix epoch: btime + starttime / CLK_TCK
};

// The fields of /proc/<pid>/stat this needs; `stat` is the file's text,
// `boot_time` the btime line of /proc/stat (seconds since the epoch).
absl::StatusOr<ProcessStats> ParseProcStat(absl::string_view stat, int64_t ticks_per_second,
                                           int64_t page_size, int64_t boot_time);

// This process's numbers now.
absl::StatusOr<ProcessStats> ReadProcessStats();

}  // namespace wavebake::web
