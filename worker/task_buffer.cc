#include "worker/task_buffer.h"

#include <memory>

namespace wavebake {
namespace {

struct Buffer {
  std::unique_ptr<float[]> data;
  size_t size = 0;
};
thread_local Buffer buffer;

}  // namespace

std::span<float> TaskBuffer(size_t floats) {
  if (buffer.size < floats) {
    buffer.data.reset();  // the old one first: never both at once
    buffer.data = std::make_unique_for_overwrite<float[]>(floats);
    buffer.size = floats;
  }
  return {buffer.data.get(), floats};
}

void ReleaseTaskBuffer() { buffer = Buffer{}; }

}  // namespace wavebake
