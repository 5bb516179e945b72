#pragma once
// Element types of the store's arrays (DESIGN.md §3) and their Zarr v2 names.
// Arrays are little-endian on disk; wavebake runs only on little-endian hosts,
// so in-memory bytes are the on-disk bytes.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace wavebake {

static_assert(std::endian::native == std::endian::little,
              "the store is little-endian and chunks are written without byte swapping");

enum class DType { kUint8, kInt16, kInt32, kUint32, kInt64, kFloat32 };

size_t ItemSize(DType dtype);
bool IsInteger(DType dtype);
// The Zarr v2 / numpy type string: "|u1", "<i2", "<i4", "<u4", "<i8", "<f4".
absl::string_view ZarrName(DType dtype);
absl::StatusOr<DType> ParseDType(absl::string_view zarr_name);

// Whether `value` is representable in `dtype` (integral and in range for
// integer types); fill values are checked with it before they are stored.
bool Representable(DType dtype, double value);
// Fills `out` (a whole number of elements) with `value` converted to `dtype`.
void FillElements(DType dtype, double value, std::span<std::byte> out);

// The DType of a C++ element type, for the typed wrappers of ZarrArray.
template <class T>
constexpr DType DTypeOf() {
  if constexpr (std::is_same_v<T, uint8_t>)
    return DType::kUint8;
  else if constexpr (std::is_same_v<T, int16_t>)
    return DType::kInt16;
  else if constexpr (std::is_same_v<T, int32_t>)
    return DType::kInt32;
  else if constexpr (std::is_same_v<T, uint32_t>)
    return DType::kUint32;
  else if constexpr (std::is_same_v<T, int64_t>)
    return DType::kInt64;
  else if constexpr (std::is_same_v<T, float>)
    return DType::kFloat32;
  else
    static_assert(sizeof(T) == 0, "no store dtype for this element type");
}

}  // namespace wavebake
