#pragma once
// A byte vector whose growth does not zero the new bytes, for buffers that
// are written in full right after they grow (a zstd frame, a file read).
// Zeroing a staging chunk's compress bound cost as much as a tenth of its
// compression, and a fresh allocation of that size faults in every page:
// a ByteBuffer kept per thread does neither once it has grown.
#include <cstddef>
#include <memory>
#include <new>
#include <vector>

namespace wavebake {

template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  // resize(n) default-initializes: for bytes, leaves them as they are.
  // Construction with arguments falls back to std::construct_at
  // (std::allocator_traits).
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
};

// Plain values that are read or decompressed straight into after a resize.
template <class T>
using DefaultInitVector = std::vector<T, DefaultInitAllocator<T>>;

using ByteBuffer = DefaultInitVector<std::byte>;

}  // namespace wavebake
