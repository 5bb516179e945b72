#pragma once
// The numcodecs "shuffle" filter ({"id": "shuffle", "elementsize": n}): the
// bytes of each chunk are regrouped by their place inside the element — all
// first bytes, then all second bytes, … For small integers (delta-coded
// transport/indices, int16 transport/data) the high bytes become long runs of
// 0x00/0xFF that zstd packs far tighter than interleaved (measured in
// docs/RESULTS.md). Debian's numcodecs 0.11 reads it.
#include <cstddef>
#include <span>

namespace wavebake {

// Whole chunks only; chunk.size() must be a multiple of element_size.
void ShuffleEncode(size_t element_size, std::span<std::byte> chunk);
void ShuffleDecode(size_t element_size, std::span<std::byte> chunk);

}  // namespace wavebake
