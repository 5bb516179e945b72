#pragma once
// Zarr v2 groups: a directory with .zgroup, and attributes in .zattrs (a JSON
// object) — the store root's manifest and the transport group's CSC
// attributes live there (DESIGN.md §3). All writes are atomic.
#include <filesystem>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "nlohmann/json.hpp"

namespace wavebake {

// Creates `dir` (and parents) and writes {"zarr_format": 2} to .zgroup.
absl::Status WriteGroup(const std::filesystem::path& dir);
// Replaces .zattrs of the group or array at `dir`; `attrs` must be an object.
// JSON has no NaN: a NaN number is written as null.
absl::Status WriteAttrs(const std::filesystem::path& dir, const nlohmann::json& attrs);
// A missing .zattrs is an empty object, as in Zarr.
absl::StatusOr<nlohmann::json> ReadAttrs(const std::filesystem::path& dir);

}  // namespace wavebake
