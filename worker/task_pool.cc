#include "worker/task_pool.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

namespace wavebake {

absl::Status RunTasks(int count, int threads, const std::function<absl::Status(int)>& task) {
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::mutex mu;
  absl::Status first_error;
  auto worker = [&] {
    for (int i = next++; i < count && !failed; i = next++) {
      absl::Status s = task(i);
      if (s.ok()) continue;
      std::lock_guard<std::mutex> lock(mu);
      if (!failed.exchange(true)) first_error = std::move(s);
    }
  };
  const int n = std::clamp(threads, 1, std::max(count, 1));
  {
    std::vector<std::jthread> pool;
    for (int t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();  // the calling thread is one of the n
  }            // jthreads join here
  return first_error;
}

}  // namespace wavebake
