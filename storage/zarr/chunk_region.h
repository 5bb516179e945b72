#pragma once
// Where a chunk sits in its array. Zarr v2 stores every chunk at full chunk
// shape: edge chunks are padded past the array's end (with the fill value).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "storage/zarr/array_spec.h"

namespace wavebake {

// Zarr v2 chunk key with the "." separator: "i.j.k".
std::string ChunkKey(std::span<const int64_t> chunk_index);

// Every chunk index of the array's chunk grid, in C order.
std::vector<std::vector<int64_t>> AllChunkIndices(const ArraySpec& spec);

// Copies the part of chunk `chunk_index` that lies inside the array between a
// whole C-order array and a full C-order chunk buffer, one contiguous row
// along the last dimension at a time. Padding bytes of the chunk are untouched.
// Sizes must match the spec (checked by the caller).
void CopyArrayToChunk(const ArraySpec& spec, std::span<const int64_t> chunk_index,
                      std::span<const std::byte> array, std::span<std::byte> chunk);
void CopyChunkToArray(const ArraySpec& spec, std::span<const int64_t> chunk_index,
                      std::span<const std::byte> chunk, std::span<std::byte> array);

}  // namespace wavebake
