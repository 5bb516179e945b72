#pragma once
// What a Zarr v2 array is (shape, chunking, dtype, fill value, codec) and its
// .zarray form (DESIGN.md §3: C order, little-endian, zstd, "." separator).
#include <cstdint>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "nlohmann/json.hpp"
#include "storage/zarr/dtype.h"
#include "storage/zarr/zstd_codec.h"

namespace wavebake {

struct ArraySpec {
  std::vector<int64_t> shape;   // ≥ 1 dimension; a dimension may be 0 (e.g. nnz = 0)
  std::vector<int64_t> chunks;  // same rank, each ≥ 1
  DType dtype = DType::kFloat32;
  double fill_value = 0;  // what a missing chunk reads as; integral for integer dtypes
  int zstd_level = kDefaultZstdLevel;
  // How the writer searches at that level: not in the .zarray and not
  // compared by SameSpec (a reader needs only the frames).
  ZstdSearch zstd_search = {};
  // numcodecs Delta filter (integer dtypes only); DESIGN.md §3 suggests it for
  // transport/indices, whose sorted runs become small differences.
  bool delta_filter = false;
  // numcodecs Shuffle filter with elementsize = the dtype's size, after delta
  // when both are on (storage/zarr/shuffle_filter.h).
  bool shuffle_filter = false;
};

// Same array: fields equal, with NaN fill values equal to each other.
bool SameSpec(const ArraySpec& a, const ArraySpec& b);

// InvalidArgument naming `source` and the bad field.
absl::Status ValidateSpec(const ArraySpec& spec, absl::string_view source = "array spec");

int64_t ElementCount(const ArraySpec& spec);            // product of shape
int64_t ChunkElementCount(const ArraySpec& spec);       // product of chunks
std::vector<int64_t> ChunkGrid(const ArraySpec& spec);  // chunks per dimension, rounded up

// The .zarray document, in the form numcodecs 0.11 accepts (no "checksum" key).
nlohmann::json ToZarray(const ArraySpec& spec);
// Parses and validates a .zarray document; errors name `source` and the field.
absl::StatusOr<ArraySpec> FromZarray(const nlohmann::json& zarray, absl::string_view source);

}  // namespace wavebake
