#pragma once
// Making a finished store visible at its output path (DESIGN.md §4: "nothing
// half-written is left behind"): the store is built beside the output and
// moved into place by one rename, so readers see the old store or the new
// one, never a mix.
#include <filesystem>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace wavebake {

// OK if `out` does not exist or is a wavebake store holding only what a bake
// writes (which a bake may replace); AlreadyExists naming "out" and the entry
// for anything else, a user's file inside a store included (replacing it
// would delete that file); InvalidArgument if its parent directory does not
// exist or `out` is a symbolic link (ResolveOutputPath first).
absl::Status CheckOutputPath(const std::filesystem::path& out);

// `out` with symbolic links of its last component followed (a link is where
// the user keeps the store: the store goes to its target), then checked by
// CheckOutputPath.
absl::StatusOr<std::filesystem::path> ResolveOutputPath(const std::filesystem::path& out);

// Moves the directory `partial` to `out`. If `out` holds a store, the two are
// swapped atomically (renameat2 RENAME_EXCHANGE) and the old one deleted;
// where the filesystem cannot exchange, the old store is renamed aside first.
absl::Status PublishStore(const std::filesystem::path& partial, const std::filesystem::path& out);

}  // namespace wavebake
