#include "storage/zarr/chunk_region.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "absl/strings/str_join.h"

namespace wavebake {
namespace {

// Calls row(array_offset, chunk_offset, count) in elements for every row of
// the chunk's in-array region.
template <class Row>
void ForEachRow(const ArraySpec& spec, std::span<const int64_t> chunk_index, Row row) {
  const size_t rank = spec.shape.size();
  std::vector<int64_t> start(rank), extent(rank);
  for (size_t d = 0; d < rank; ++d) {
    start[d] = chunk_index[d] * spec.chunks[d];
    extent[d] = std::min(spec.chunks[d], spec.shape[d] - start[d]);
    if (extent[d] <= 0) return;  // empty region (zero-length dimension)
  }
  std::vector<int64_t> pos(rank, 0);  // position inside the region; the last dim stays 0
  while (true) {
    int64_t array_offset = 0, chunk_offset = 0;
    for (size_t d = 0; d < rank; ++d) {
      array_offset = array_offset * spec.shape[d] + start[d] + pos[d];
      chunk_offset = chunk_offset * spec.chunks[d] + pos[d];
    }
    row(array_offset, chunk_offset, extent[rank - 1]);
    // Odometer over every dimension but the last.
    size_t d = rank - 1;
    while (d > 0 && ++pos[d - 1] == extent[d - 1]) pos[--d] = 0;
    if (d == 0) return;
  }
}

}  // namespace

std::string ChunkKey(std::span<const int64_t> chunk_index) {
  return absl::StrJoin(chunk_index, ".");
}

std::vector<std::vector<int64_t>> AllChunkIndices(const ArraySpec& spec) {
  const std::vector<int64_t> grid = ChunkGrid(spec);
  std::vector<std::vector<int64_t>> all;
  for (int64_t n : grid) {
    if (n == 0) return all;
  }
  std::vector<int64_t> index(grid.size(), 0);
  while (true) {
    all.push_back(index);
    size_t d = grid.size();
    while (d > 0 && ++index[d - 1] == grid[d - 1]) index[--d] = 0;
    if (d == 0) return all;
  }
}

void CopyArrayToChunk(const ArraySpec& spec, std::span<const int64_t> chunk_index,
                      std::span<const std::byte> array, std::span<std::byte> chunk) {
  const size_t item = ItemSize(spec.dtype);
  ForEachRow(spec, chunk_index, [&](int64_t a, int64_t c, int64_t n) {
    std::memcpy(chunk.data() + c * item, array.data() + a * item, n * item);
  });
}

void CopyChunkToArray(const ArraySpec& spec, std::span<const int64_t> chunk_index,
                      std::span<const std::byte> chunk, std::span<std::byte> array) {
  const size_t item = ItemSize(spec.dtype);
  ForEachRow(spec, chunk_index, [&](int64_t a, int64_t c, int64_t n) {
    std::memcpy(array.data() + a * item, chunk.data() + c * item, n * item);
  });
}

}  // namespace wavebake
