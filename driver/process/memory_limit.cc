#include "driver/process/memory_limit.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace wavebake::driver {
namespace {

std::string ReadSmallFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The limit files that may cap this process: its own cgroup's and, where a
// container shows its cgroup as the root, the root's (v2, then v1).
std::vector<std::string> LimitFiles() {
  std::vector<std::string> files = {"/sys/fs/cgroup/memory.max",
                                    "/sys/fs/cgroup/memory/memory.limit_in_bytes"};
  std::istringstream lines(ReadSmallFile("/proc/self/cgroup"));
  for (std::string line; std::getline(lines, line);) {
    // "0::/PATH" (v2) or "N:CONTROLLERS:/PATH" (v1, e.g. "4:memory:/a/b").
    const size_t c1 = line.find(':'), c2 = line.find(':', c1 + 1);
    if (c1 == std::string::npos || c2 == std::string::npos) continue;
    const std::string id = line.substr(0, c1), controllers = line.substr(c1 + 1, c2 - c1 - 1),
                      path = line.substr(c2 + 1);
    if (path.empty() || path == "/") continue;
    if (id == "0" && controllers.empty()) files.push_back("/sys/fs/cgroup" + path + "/memory.max");
    if (("," + controllers + ",").find(",memory,") != std::string::npos)
      files.push_back("/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes");
  }
  return files;
}

}  // namespace

std::optional<uint64_t> ParseCgroupLimit(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  uint64_t bytes = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), bytes);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return bytes;
}

uint64_t UsableMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  uint64_t usable = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : uint64_t{1} << 30;
  for (const std::string& file : LimitFiles()) {
    if (const std::optional<uint64_t> limit = ParseCgroupLimit(ReadSmallFile(file)))
      usable = std::min(usable, *limit);
  }
  return usable;
}

}  // namespace wavebake::driver
