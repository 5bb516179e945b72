#pragma once
// Reads a slice [begin, end) of a 1-D Zarr array, touching only the chunks
// that cover it (one column of a CSC store, DESIGN.md §3, without reading
// the whole of transport/indices and data).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "storage/zarr/zarr_array.h"

namespace wavebake {

template <class T>
absl::StatusOr<std::vector<T>> ReadRange(const ZarrArray& array, int64_t begin, int64_t end) {
  const int64_t length = array.spec().shape.at(0);
  if (array.spec().shape.size() != 1 || begin < 0 || end < begin || end > length) {
    return absl::InvalidArgumentError(absl::StrCat(array.dir().string(), ": range [", begin, ", ",
                                                   end, ") outside [0, ", length, ")"));
  }
  const int64_t chunk = array.spec().chunks.at(0);
  std::vector<T> out;
  out.reserve(static_cast<size_t>(end - begin));
  for (int64_t c = begin / chunk; c * chunk < end; ++c) {
    absl::StatusOr<std::vector<T>> values = array.ReadChunk<T>(std::span(&c, 1));
    if (!values.ok()) return values.status();
    const int64_t lo = std::max(begin, c * chunk) - c * chunk;
    const int64_t hi = std::min(end, (c + 1) * chunk) - c * chunk;
    out.insert(out.end(), values->begin() + lo, values->begin() + hi);
  }
  return out;
}

}  // namespace wavebake
