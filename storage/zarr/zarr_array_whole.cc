// ZarrArray::WriteAll / ReadAll: a whole in-memory array to and from chunks.
#include "absl/strings/str_cat.h"
#include "storage/zarr/chunk_region.h"
#include "storage/zarr/zarr_array.h"

namespace wavebake {
namespace {

absl::Status CheckSize(const ZarrArray& array, size_t bytes) {
  const size_t expected =
      static_cast<size_t>(ElementCount(array.spec())) * ItemSize(array.spec().dtype);
  if (bytes == expected) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat(array.dir().string(), ": whole-array data is ",
                                                 bytes, " bytes, the array is ", expected));
}

}  // namespace

absl::Status ZarrArray::WriteAllBytes(std::span<const std::byte> values) const {
  if (absl::Status s = CheckSize(*this, values.size()); !s.ok()) return s;
  std::vector<std::byte> chunk(chunk_bytes());
  for (const std::vector<int64_t>& index : AllChunkIndices(spec_)) {
    // Pad edge chunks with the fill value, as Zarr does, so stores are deterministic.
    FillElements(spec_.dtype, spec_.fill_value, chunk);
    CopyArrayToChunk(spec_, index, values, chunk);
    if (absl::Status s = WriteChunk(index, chunk); !s.ok()) return s;
  }
  return absl::OkStatus();
}

absl::Status ZarrArray::ReadAllBytes(std::span<std::byte> out) const {
  if (absl::Status s = CheckSize(*this, out.size()); !s.ok()) return s;
  std::vector<std::byte> chunk(chunk_bytes());
  for (const std::vector<int64_t>& index : AllChunkIndices(spec_)) {
    if (absl::Status s = ReadChunkInto(index, chunk); !s.ok()) return s;
    CopyChunkToArray(spec_, index, chunk, out);
  }
  return absl::OkStatus();
}

}  // namespace wavebake
