#pragma once
// JSON metadata files of the store (.zarray, .zgroup, .zattrs), written atomically.
#include <filesystem>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "nlohmann/json.hpp"

namespace wavebake {

// Keys come out sorted (nlohmann objects are ordered maps), so the same
// metadata is the same bytes: stores are bit-identical (DESIGN.md §1).
absl::Status WriteJsonFile(const std::filesystem::path& path, const nlohmann::json& value);
// NotFound if the file is missing; InvalidArgument naming the file if it is not JSON.
absl::StatusOr<nlohmann::json> ReadJsonFile(const std::filesystem::path& path);

}  // namespace wavebake
