#pragma once
// Making a finished store visible at its output path (DESIGN.md §4: "nothing
// half-written is left behind"): the store is built beside the output and
// moved into place by one rename, so readers see the old store or the new
// one, never a mix.
#include <filesystem>

#include "absl/status/status.h"

namespace wavebake {

// OK if `out` does not exist or is a wavebake store (which a bake may
// replace); AlreadyExists naming "out" for anything else; InvalidArgument if
// its parent directory does not exist.
absl::Status CheckOutputPath(const std::filesystem::path& out);

// Moves the directory `partial` to `out`. If `out` holds a store, the two are
// swapped atomically (renameat2 RENAME_EXCHANGE) and the old one deleted;
// where the filesystem cannot exchange, the old store is renamed aside first.
absl::Status PublishStore(const std::filesystem::path& partial, const std::filesystem::path& out);

}  // namespace wavebake
