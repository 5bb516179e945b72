#pragma once
// Whole-file writes that never leave a half-written file behind: the bytes go
// to a temporary file in the same directory, are flushed to disk, then
// renamed over the target (rename is atomic within a filesystem).
//
// Local to runtime/ for now; storage/atomic_file.h (AtomicWriteFile, same
// signature) is meant to replace it once both branches meet.
#include <cstddef>
#include <filesystem>
#include <span>

#include "absl/status/status.h"

namespace wavebake {

absl::Status WriteFileAtomically(const std::filesystem::path& path,
                                 std::span<const std::byte> bytes);

}  // namespace wavebake
