#pragma once
// Partial stores nobody will finish (DESIGN.md §4: "nothing half-written is
// left behind"): a job's partial directory (proto/bake_request.h
// PartialStorePath) outlives its job when the coordinator died between the
// planner's reservation and the job's commit, or, before submits were
// transactional, when the commit failed. Such a directory holds its job's
// disk space and blocks the next job of that name (the planner reserves a
// name by creating the directory), so the coordinator removes every one
// that belongs to no unfinished job when it starts, before it serves.
#include <filesystem>
#include <set>
#include <string>

#include "absl/status/statusor.h"

namespace wavebake {

// Removes each directory ".NAME.partial" directly under store_root whose
// store path NAME is not in `live` (the store paths of the unfinished jobs);
// returns how many it removed. Files, other directories and stores are left.
absl::StatusOr<int> RemoveOrphanPartialStores(const std::filesystem::path& store_root,
                                              const std::set<std::string>& live);

}  // namespace wavebake
