#pragma once
// Per-thread reusable float buffers for the wavelet steps: a 1024² step needs
// a 4 MB block buffer, and allocating it per step (per column, per depth in
// the bake) would cost more page faults than the transform itself. Each slot
// grows to the largest size asked for on that thread and is never shrunk.
#include <cstddef>
#include <span>

namespace wavebake {

enum class ScratchSlot { kLine, kBlock, kCount };

// A buffer of at least n floats, contents unspecified; valid until the next
// call with the same slot on this thread.
std::span<float> ThreadScratch(ScratchSlot slot, size_t n);

}  // namespace wavebake
