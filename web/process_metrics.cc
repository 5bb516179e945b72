#include "web/process_metrics.h"

#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"

namespace wavebake::web {
namespace {

absl::StatusOr<std::string> Slurp(const char* path) {
  std::ifstream in(path);
  if (!in) return absl::UnavailableError(std::string("cannot read ") + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The "btime" line of /proc/stat: boot time in seconds since the epoch.
absl::StatusOr<int64_t> BootTime() {
  absl::StatusOr<std::string> text = Slurp("/proc/stat");
  if (!text.ok()) return text.status();
  for (absl::string_view line : absl::StrSplit(*text, '\n')) {
    int64_t v = 0;
    if (absl::StartsWith(line, "btime ") && absl::SimpleAtoi(line.substr(6), &v)) return v;
  }
  return absl::DataLossError("/proc/stat has no btime line");
}

}  // namespace

absl::StatusOr<ProcessStats> ParseProcStat(absl::string_view stat, int64_t ticks_per_second,
                                           int64_t page_size, int64_t boot_time) {
  // Field 2 (comm) is parenthesised and may hold spaces or ')': the fields
  // after it start past the last ')' (proc(5)).
  const size_t close = stat.rfind(')');
  if (close == absl::string_view::npos || ticks_per_second <= 0)
    return absl::DataLossError("/proc/self/stat: no command field");
  const std::vector<absl::string_view> f =
      absl::StrSplit(stat.substr(close + 1), ' ', absl::SkipEmpty());
  // f[0] is field 3 (state): field n is f[n - 3].
  constexpr size_t kUtime = 14 - 3, kStime = 15 - 3, kStart = 22 - 3, kVsize = 23 - 3,
                   kRss = 24 - 3;
  if (f.size() <= kRss) return absl::DataLossError("/proc/self/stat: too few fields");
  int64_t utime = 0, stime = 0, start = 0, vsize = 0, rss = 0;
  if (!absl::SimpleAtoi(f[kUtime], &utime) || !absl::SimpleAtoi(f[kStime], &stime) ||
      !absl::SimpleAtoi(f[kStart], &start) || !absl::SimpleAtoi(f[kVsize], &vsize) ||
      !absl::SimpleAtoi(f[kRss], &rss))
    return absl::DataLossError("/proc/self/stat: a field is not a number");
  ProcessStats p;
  const double tps = static_cast<double>(ticks_per_second);
  p.cpu_seconds = static_cast<double>(utime + stime) / tps;
  p.start_time_seconds = static_cast<double>(boot_time) + static_cast<double>(start) / tps;
  p.virtual_bytes = vsize;
  p.resident_bytes = rss * page_size;
  return p;
}

absl::StatusOr<ProcessStats> ReadProcessStats() {
  absl::StatusOr<std::string> stat = Slurp("/proc/self/stat");
  if (!stat.ok()) return stat.status();
  absl::StatusOr<int64_t> boot = BootTime();
  if (!boot.ok()) return boot.status();
  absl::StatusOr<ProcessStats> p =
      ParseProcStat(*stat, sysconf(_SC_CLK_TCK), sysconf(_SC_PAGESIZE), *boot);
  if (!p.ok()) return p;
  std::error_code ec;
  int64_t fds = 0;
  for (std::filesystem::directory_iterator it("/proc/self/fd", ec), end; !ec && it != end;
       it.increment(ec)) {
    ++fds;
  }
  // The iterator's own descriptor was open while it counted.
  p->open_fds = fds > 0 ? fds - 1 : 0;
  rlimit lim{};
  if (getrlimit(RLIMIT_NOFILE, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY)
    p->max_fds = static_cast<int64_t>(lim.rlim_cur);
  return p;
}

}  // namespace wavebake::web
