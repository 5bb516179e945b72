#pragma once
// What whoever schedules a task may share with the running task function,
// without the function knowing anything of scheduling (DESIGN.md §4): a flag
// that asks it to stop early (the worker's lease was withdrawn), and a live
// counter it publishes as it goes (for heartbeats' progress reports). Both
// optional; the task functions of DESIGN.md §2 take `const TaskSignals&`.
#include <atomic>
#include <cstdint>

namespace wavebake {

struct TaskSignals {
  const std::atomic<bool>* cancel = nullptr;     // true: return Cancelled soon, write no more
  std::atomic<uint64_t>* rays_traced = nullptr;  // the task's running total
};

}  // namespace wavebake
