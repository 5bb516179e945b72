#include "worker/loop/context_cache.h"

#include <algorithm>

namespace wavebake {

absl::StatusOr<ContextCache::Context> ContextCache::Get(const std::string& key,
                                                        const BuildFn& build) {
  std::shared_future<Result> pending;
  std::promise<Result> promise;
  uint64_t serial = 0;
  {
    std::lock_guard lock(mu_);
    auto it = std::find_if(entries_.begin(), entries_.end(),
                           [&](const Entry& e) { return e.key == key; });
    if (it != entries_.end()) {
      entries_.splice(entries_.begin(), entries_, it);
      pending = it->result;
    } else {
      serial = ++builds_;
      entries_.push_front({key, serial, promise.get_future().share()});
      while (entries_.size() > capacity_) entries_.pop_back();
    }
  }
  if (pending.valid()) return pending.get();  // built, or being built by another thread

  // Built outside the lock: tasks of other jobs go on meanwhile.
  absl::StatusOr<std::unique_ptr<BakeContext>> built = build();
  Result result = built.ok() ? Result(Context(std::move(*built))) : Result(built.status());
  promise.set_value(result);
  if (!result.ok()) {
    std::lock_guard lock(mu_);
    entries_.remove_if([&](const Entry& e) { return e.serial == serial; });
  }
  return result;
}

size_t ContextCache::builds() const {
  std::lock_guard lock(mu_);
  return builds_;
}

}  // namespace wavebake
