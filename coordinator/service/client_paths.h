#pragma once
// Messages that reach a remote client carry no path of the server (DESIGN.md
// §4): where the coordinator's data directory or store root appears in an
// error — a planner's, a worker's task failure, an I/O error — it is replaced
// by a label before the message leaves the JobService.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace wavebake {

class ClientPaths {
 public:
  // Redacts `dir` (as given and as an absolute, normal path) to `label`.
  void Hide(const std::filesystem::path& dir, const std::string& label);
  std::string operator()(std::string message) const;

 private:
  std::vector<std::pair<std::string, std::string>> hidden_;  // longest first
};

}  // namespace wavebake
