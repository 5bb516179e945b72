#include "core/util/parallel_for.h"

#include <mutex>

namespace wavebake {

absl::Status ParallelTasks(int count, int threads, const std::function<absl::Status(int)>& task) {
  std::atomic<int> next{0};
  std::mutex mu;
  absl::Status first;  // guarded by mu
  auto work = [&] {
    for (int i; (i = next.fetch_add(1)) < count;) {
      absl::Status s = task(i);
      if (s.ok()) continue;
      std::lock_guard lock(mu);
      if (first.ok()) first = std::move(s);
      next = count;  // no new task starts
    }
  };
  {
    std::vector<std::jthread> pool;
    for (int t = 1; t < std::max(threads, 1); ++t) pool.emplace_back(work);
    work();
  }
  return first;
}

}  // namespace wavebake
