#include "worker/tiles/changed_columns.h"

#include <bit>

#include "absl/strings/str_cat.h"
#include "storage/files/atomic_file.h"
#include "storage/store/store_layout.h"

namespace wavebake {
namespace {

std::filesystem::path RecordPath(const std::filesystem::path& store, int tile) {
  return store::Path(store, store::kStagingChanged) / std::to_string(tile);
}

}  // namespace

void OrChangedColumns(const OldRows& old, std::span<const float> rows, size_t stride,
                      std::span<uint8_t> changed) {
  const size_t columns = changed.size();
  for (size_t k = 0; k < old.cells.size(); ++k) {
    const float* __restrict now = rows.data() + size_t(old.cells[k]) * stride;
    const float* __restrict was = old.values.data() + k * columns;
    uint8_t* __restrict mark = changed.data();  // bytes alias anything: restrict, to vectorize
    // Bits, not values: -0 and 0 are stored differently (as a memcmp of the chunks sees them).
    for (size_t m = 0; m < columns; ++m)
      mark[m] |=
          static_cast<uint8_t>(std::bit_cast<uint32_t>(now[m]) != std::bit_cast<uint32_t>(was[m]));
  }
}

absl::Status WriteChangedColumns(const std::filesystem::path& store, int tile,
                                 std::span<const uint8_t> changed) {
  std::vector<std::byte> bits((changed.size() + 7) / 8, std::byte{0});
  for (size_t m = 0; m < changed.size(); ++m)
    if (changed[m]) bits[m / 8] |= std::byte(1u << (m % 8));
  if (absl::Status s = CreateDirectories(store::Path(store, store::kStagingChanged)); !s.ok())
    return s;
  return AtomicWriteFile(RecordPath(store, tile), bits);
}

absl::Status OrChangedColumns(const std::filesystem::path& store, int tile, int first,
                              std::span<uint8_t> changed) {
  absl::StatusOr<std::vector<std::byte>> bits = ReadFile(RecordPath(store, tile));
  if (!bits.ok()) return bits.status();
  if (bits->size() * 8 < first + changed.size())
    return absl::DataLossError(absl::StrCat(RecordPath(store, tile).string(), ": ", bits->size(),
                                            " bytes, too short for column ",
                                            first + changed.size() - 1));
  for (size_t j = 0; j < changed.size(); ++j) {
    const size_t m = first + j;
    changed[j] |= uint8_t(std::to_integer<unsigned>((*bits)[m / 8] >> (m % 8)) & 1u);
  }
  return absl::OkStatus();
}

void RemoveChangedColumns(const std::filesystem::path& store) {
  std::error_code ec;
  std::filesystem::remove_all(store::Path(store, store::kStagingChanged), ec);
}

}  // namespace wavebake
