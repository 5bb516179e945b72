#pragma once
// A whole store reads back (DESIGN.md §3): its manifest, its final arrays
// complete and consistent with it (storage/store/store_check.h), and every chunk of
// every array under it, each zstd frame with its content checksum — what a
// client checks before trusting a store it did not write (`wavebake fetch`).
#include <filesystem>

#include "absl/status/statusor.h"

namespace wavebake {

// The number of arrays; the first error met (DATA_LOSS naming the chunk for
// a damaged one) otherwise.
absl::StatusOr<int> VerifyStore(const std::filesystem::path& store);

}  // namespace wavebake
