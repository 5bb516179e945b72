#pragma once
// BakeContexts of the jobs a worker is working on (worker/tiles/bake_context.h):
// built once per job by the first thread that needs one, while the others
// wait for it, then shared read-only by every task of the job. Building one
// loads the scene, lays out the samples and builds the Embree scene — far too
// much to repeat per task.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <future>
#include <list>
#include <memory>
#include <mutex>
#include <string>

#include "absl/status/statusor.h"
#include "worker/tiles/bake_context.h"

namespace wavebake {

class ContextCache {
 public:
  using Context = std::shared_ptr<const BakeContext>;
  using BuildFn = std::function<absl::StatusOr<std::unique_ptr<BakeContext>>()>;

  // Keeps the `capacity` most recently used contexts (tasks still holding an
  // evicted one keep it alive).
  explicit ContextCache(size_t capacity = 4) : capacity_(capacity < 1 ? 1 : capacity) {}

  // The context cached under `key`, or build() run once for it. `key` must
  // name everything the context depends on (the worker uses the job id and
  // the job's serialized request). A failed build is returned to the threads
  // waiting for it and not kept: a later call tries again.
  absl::StatusOr<Context> Get(const std::string& key, const BuildFn& build);

  size_t builds() const;  // contexts built so far (tests: "once per job")

 private:
  using Result = absl::StatusOr<Context>;
  struct Entry {
    std::string key;
    uint64_t serial = 0;  // tells this build from a later one under the same key
    std::shared_future<Result> result;
  };

  mutable std::mutex mu_;
  std::list<Entry> entries_;  // most recently used first
  size_t capacity_;
  size_t builds_ = 0;
};

}  // namespace wavebake
