#include "worker/loop/task_buffer.h"

#include <sys/mman.h>

#include <memory>
#include <new>

namespace wavebake {
namespace {

struct Unmap {
  size_t bytes;
  void operator()(float* p) const { ::munmap(p, bytes); }
};

struct Buffer {
  std::unique_ptr<float[], Unmap> data{nullptr, Unmap{0}};
  size_t size = 0;
};
thread_local Buffer buffer;

// The usual transparent huge page; rounding the mapping up to it lets the
// kernel back the whole buffer with huge pages.
constexpr size_t kHugePage = size_t{2} << 20;

}  // namespace

std::span<float> TaskBuffer(size_t floats) {
  if (buffer.size < floats) {
    buffer = Buffer{};  // the old one first: never both at once
    const size_t bytes = (floats * sizeof(float) + kHugePage - 1) / kHugePage * kHugePage;
    void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    ::madvise(p, bytes, MADV_HUGEPAGE);
    buffer.data = std::unique_ptr<float[], Unmap>(static_cast<float*>(p), Unmap{bytes});
    buffer.size = floats;
  }
  return {buffer.data.get(), floats};
}

void ReleaseTaskBuffer() { buffer = Buffer{}; }

}  // namespace wavebake
