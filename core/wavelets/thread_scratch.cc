#include "core/wavelets/thread_scratch.h"

#include <array>
#include <vector>

namespace wavebake {

std::span<float> ThreadScratch(ScratchSlot slot, size_t n) {
  thread_local std::array<std::vector<float>, static_cast<size_t>(ScratchSlot::kCount)> buffers;
  std::vector<float>& buf = buffers[static_cast<size_t>(slot)];
  if (buf.size() < n) buf.resize(n);
  return std::span<float>(buf).first(n);
}

}  // namespace wavebake
