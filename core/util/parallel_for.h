#pragma once
// Minimal parallel loops over [0, count). Callers make every index write its
// own output, so the result does not depend on the number of threads or
// their timing.
#include <algorithm>
#include <atomic>
#include <functional>
#include <thread>
#include <vector>

#include "absl/status/status.h"

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

// body(worker, i) for i in [0, count) on `threads` threads (0: all cores),
// worker ∈ [0, threads) naming the thread, so callers can keep one scratch
// per worker. Indices go out in blocks of `block` for locality.
template <typename Body>
void ParallelForWorkers(int count, int threads, int block, const Body& body) {
  if (threads <= 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  const int blocks = (count + block - 1) / std::max(block, 1);
  threads = std::clamp(threads, 1, std::max(blocks, 1));
  std::atomic<int> next{0};
  auto work = [&](int worker) {
    for (int b; (b = next.fetch_add(1)) < blocks;) {
      const int end = std::min(count, (b + 1) * block);
      for (int i = b * block; i < end; ++i) body(worker, i);
    }
  };
  std::vector<std::jthread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
}

// body(state, begin, end) over [0, count) in chunks of `chunk`, on `threads`
// threads (≤ 0: all cores), each with its own state = make_state(). Chunks
// are handed out round-robin, which balances uneven work; each index is
// still computed by the same code whichever thread takes it.
template <typename MakeState, typename Body>
void ParallelChunks(int count, int chunk, int threads, const MakeState& make_state,
                    const Body& body) {
  const int chunks = (count + chunk - 1) / chunk;
  std::atomic<int> next{0};
  auto work = [&] {
    auto state = make_state();
    for (int c; (c = next.fetch_add(1)) < chunks;)
      body(state, c * chunk, std::min(count, (c + 1) * chunk));
  };
  if (threads <= 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, std::max(chunks, 1));
  std::vector<std::jthread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
}

// task(i) for i in [0, count) on `threads` threads (at least 1; the caller's
// is one of them): tasks that can fail, like a job's tiles or column groups
// run in one process. The first error stops new tasks and is returned once
// the running ones end.
absl::Status ParallelTasks(int count, int threads, const std::function<absl::Status(int)>& task);

}  // namespace wavebake
