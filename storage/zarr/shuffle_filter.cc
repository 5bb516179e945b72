#include "storage/zarr/shuffle_filter.h"

#include <algorithm>
#include <vector>

namespace wavebake {

void ShuffleEncode(size_t element_size, std::span<std::byte> chunk) {
  if (element_size <= 1) return;
  const size_t count = chunk.size() / element_size;
  std::vector<std::byte> out(chunk.size());
  for (size_t i = 0; i < count; ++i)
    for (size_t j = 0; j < element_size; ++j) out[j * count + i] = chunk[i * element_size + j];
  std::copy(out.begin(), out.end(), chunk.begin());
}

void ShuffleDecode(size_t element_size, std::span<std::byte> chunk) {
  if (element_size <= 1) return;
  const size_t count = chunk.size() / element_size;
  std::vector<std::byte> out(chunk.size());
  for (size_t i = 0; i < count; ++i)
    for (size_t j = 0; j < element_size; ++j) out[i * element_size + j] = chunk[j * count + i];
  std::copy(out.begin(), out.end(), chunk.begin());
}

}  // namespace wavebake
