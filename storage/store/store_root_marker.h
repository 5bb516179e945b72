#pragma once
// The identity of a store root (DESIGN.md §4 data plane): the coordinator
// writes <store root>/.wavebake-store-root once, with a random id, and tells
// every worker that id when it registers. A worker compares it with the marker
// it finds at its own --store-root before it leases anything, so a wrong
// path (the coordinator's data dir instead of its store/, an NFS mount that
// is missing, another coordinator's root) is refused at start instead of
// failing tasks until the job runs out of attempts.
#include <filesystem>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace wavebake {

inline constexpr char kStoreRootMarker[] = ".wavebake-store-root";

// The id in root's marker; writes a new marker (a fresh random id) if there
// is none. Concurrent callers of one root agree on one id.
absl::StatusOr<std::string> EnsureStoreRootMarker(const std::filesystem::path& root);

// The id in root's marker. NotFound when there is none; FailedPrecondition
// when the file is not a marker.
absl::StatusOr<std::string> ReadStoreRootMarker(const std::filesystem::path& root);

// The checks a worker makes before its first lease: root is a directory, is
// writable and, unless `expected_id` is empty (a coordinator that writes no
// marker), holds the marker with that id. Errors are
// FailedPrecondition and name the path as "--store-root PATH", what was found,
// what was expected and, when the marker is one level down (PATH/store), that
// directory.
absl::Status CheckWorkerStoreRoot(const std::filesystem::path& root,
                                  const std::string& expected_id);

}  // namespace wavebake
