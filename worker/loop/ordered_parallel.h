#pragma once
// Work on items 0..count−1 spread over threads, results taken in order: the
// shape of FINALIZE, whose groups are read and quantized independently but
// appended to the store's arrays one after the other. FINALIZE runs alone at
// the end of a job, so its worker's other cores would otherwise be idle.
#include <algorithm>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace wavebake {

// produce(i) runs on `threads` threads (at least 1), at most `window` items
// ahead of the consumer (memory: window results at a time); consume(i, result)
// runs on the calling thread for i = 0, 1, … in order. The first error, from
// either, stops the rest: no produce starts after it, and it is returned
// once every started produce has ended.
template <class T>
absl::Status OrderedParallel(int count, int threads, int window,
                             const std::function<absl::StatusOr<T>(int)>& produce,
                             const std::function<absl::Status(int, T&)>& consume) {
  window = std::max(window, 1);
  std::mutex mu;
  std::condition_variable changed;
  int next = 0, consumed = 0;                                   // guarded by mu
  bool stop = false;                                            // guarded by mu
  std::vector<std::optional<absl::StatusOr<T>>> slots(window);  // item i in slot i % window

  auto work = [&] {
    std::unique_lock lock(mu);
    while (true) {
      changed.wait(lock, [&] { return stop || next >= count || next < consumed + window; });
      if (stop || next >= count) return;
      const int i = next++;
      lock.unlock();
      absl::StatusOr<T> result = produce(i);
      lock.lock();
      slots[i % window] = std::move(result);
      changed.notify_all();
    }
  };
  absl::Status first;
  {
    std::vector<std::jthread> pool;
    for (int t = 0; t < std::max(threads, 1); ++t) pool.emplace_back(work);
    for (int i = 0; i < count && first.ok(); ++i) {
      std::optional<absl::StatusOr<T>> item;
      {
        std::unique_lock lock(mu);
        changed.wait(lock, [&] { return slots[i % window].has_value(); });
        item = std::move(slots[i % window]);
        slots[i % window].reset();
      }
      first = item->ok() ? consume(i, **item) : item->status();
      std::lock_guard lock(mu);
      ++consumed;
      if (!first.ok()) stop = true;
      changed.notify_all();
    }
    if (first.ok()) return first;
    std::lock_guard lock(mu);
    stop = true;
    changed.notify_all();
  }  // the pool joins here: no produce outlives the call
  return first;
}

}  // namespace wavebake
