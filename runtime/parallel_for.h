#pragma once
// A minimal deterministic parallel loop: body(i) for i in [0, count) on all
// cores. Callers make every index write its own output, so the result does
// not depend on the number of threads or their timing.
#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace wavebake {

template <typename Body>
void ParallelFor(int count, const Body& body) {
  const int threads =
      std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, std::max(count, 1));
  std::atomic<int> next{0};
  auto work = [&] {
    for (int i; (i = next.fetch_add(1)) < count;) body(i);
  };
  std::vector<std::jthread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
}

}  // namespace wavebake
