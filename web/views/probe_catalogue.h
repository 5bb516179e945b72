#pragma once
// The environments the relight view offers (DESIGN.md §4 security: input
// from a remote client never names a file on the server): the built-ins and
// the .hdr/.exr files found under the operator's --probes DIR when the
// server starts. A client picks one by its name in this list; the name is
// looked up, never opened as a path.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace wavebake::web {

class ProbeCatalogue {
 public:
  // Built-ins only.
  ProbeCatalogue();
  // The built-ins and every regular .hdr/.exr file under dir (recursively,
  // named by its '/'-separated path relative to dir). Error: dir is not a
  // readable directory (named as --probes).
  static absl::StatusOr<ProbeCatalogue> Scan(const std::filesystem::path& dir);

  std::vector<std::string> names() const;  // built-ins first, then files by name
  // The LoadEnvMap spec of a listed name; NOT_FOUND naming `probe` otherwise.
  absl::StatusOr<std::string> Spec(const std::string& name) const;

 private:
  std::vector<std::string> order_;
  std::map<std::string, std::string> specs_;  // name -> LoadEnvMap spec
};

}  // namespace wavebake::web
