#include "storage/zarr/dtype.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

struct DTypeInfo {
  DType dtype;
  absl::string_view name;
  size_t size;
};

constexpr DTypeInfo kInfos[] = {
    {DType::kUint8, "|u1", 1},  {DType::kInt16, "<i2", 2}, {DType::kInt32, "<i4", 4},
    {DType::kUint32, "<u4", 4}, {DType::kInt64, "<i8", 8}, {DType::kFloat32, "<f4", 4},
};

const DTypeInfo& Info(DType dtype) { return kInfos[static_cast<int>(dtype)]; }

template <class T>
bool InRange(double value) {
  if constexpr (std::is_floating_point_v<T>) {
    return true;  // NaN, ±inf and rounding are all fine for a float fill value
  } else {
    // [min, 2^digits) bounds T exactly; both bounds are exact doubles, which
    // double(max) is not for 64-bit T.
    const double upper = std::ldexp(1.0, std::numeric_limits<T>::digits);
    return std::trunc(value) == value && value >= double(std::numeric_limits<T>::min()) &&
           value < upper;
  }
}

template <class T>
void Fill(double value, std::span<std::byte> out) {
  const T v = static_cast<T>(value);
  for (size_t i = 0; i + sizeof(T) <= out.size(); i += sizeof(T)) {
    std::memcpy(out.data() + i, &v, sizeof(T));
  }
}

// Calls f.template operator()<T>() with T the C++ type of `dtype`.
template <class F>
auto Visit(DType dtype, F&& f) {
  switch (dtype) {
    case DType::kUint8:
      return f.template operator()<uint8_t>();
    case DType::kInt16:
      return f.template operator()<int16_t>();
    case DType::kInt32:
      return f.template operator()<int32_t>();
    case DType::kUint32:
      return f.template operator()<uint32_t>();
    case DType::kInt64:
      return f.template operator()<int64_t>();
    case DType::kFloat32:
      break;
  }
  return f.template operator()<float>();
}

}  // namespace

size_t ItemSize(DType dtype) { return Info(dtype).size; }
bool IsInteger(DType dtype) { return dtype != DType::kFloat32; }
absl::string_view ZarrName(DType dtype) { return Info(dtype).name; }

absl::StatusOr<DType> ParseDType(absl::string_view zarr_name) {
  for (const DTypeInfo& info : kInfos) {
    if (info.name == zarr_name) return info.dtype;
  }
  return absl::InvalidArgumentError(
      absl::StrCat("unsupported dtype \"", zarr_name, "\" (expected |u1 <i2 <i4 <u4 <i8 <f4)"));
}

bool Representable(DType dtype, double value) {
  return Visit(dtype, [&]<class T>() { return InRange<T>(value); });
}

void FillElements(DType dtype, double value, std::span<std::byte> out) {
  Visit(dtype, [&]<class T>() { Fill<T>(value, out); });
}

}  // namespace wavebake
