#pragma once
// One leased task as a worker runs it (DESIGN.md §2): the task's scene and
// job context, the job's partial store directory, then the task function —
// BAKE_TILE → CreateStaging (idempotent) + BakeTile, TRANSFORM_COLUMNS →
// TransformColumns, FINALIZE shard k → FinalizeShard, FINALIZE's last task
// → FinalizeStore and the rename that makes the store appear at its path
// whole. No RPC here (worker/loop/worker_loop.h leases,
// heartbeats and reports); no scheduling in the task functions.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>

#include "absl/status/statusor.h"
#include "wavebake.pb.h"
#include "worker/loop/context_cache.h"
#include "worker/loop/scene_cache.h"
#include "worker/tiles/memory_staging.h"

namespace wavebake {

struct TaskEnv {
  std::filesystem::path store_root;  // shared with the coordinator (--store-root)
  SceneCache* scenes = nullptr;
  ContextCache* contexts = nullptr;
  SceneCache::FetchFn fetch;  // FetchScene from the coordinator
  // Threads a task may run on: the worker's --threads (the CPUs its Slurm
  // step or pod was given), never the host's hardware_concurrency().
  int threads = 1;
  // Staging chunks held in memory (worker/tiles/memory_staging.h): only where
  // every task of a job runs in this process (the embedded bake). Not owned.
  MemoryStaging* memory_staging = nullptr;
};

// Shared between the running task and the heartbeat thread.
struct TaskProgress {
  std::atomic<bool> cancel{false};       // the lease is gone: stop, report nothing
  std::atomic<uint64_t> rays_traced{0};  // live while BAKE_TILE runs (worker/loop/task_signals.h)
  std::atomic<uint64_t> bytes_written{0};
};

struct TaskOutcome {
  int64_t rays_traced = 0;
  int64_t bytes_written = 0;
  std::string stats_json;  // FINALIZE: the store's stats (they become the job's)
};

// Errors: the task's own, CancelledError once progress.cancel is seen (tasks
// check it between rows or columns), FailedPrecondition when this worker's
// plan of the job differs from the coordinator's (tiles / groups).
absl::StatusOr<TaskOutcome> RunTask(const v1::Task& task, const TaskEnv& env,
                                    TaskProgress& progress);

// FINALIZE's last step: `partial` becomes `out` by one rename. Succeeds too
// when another worker's FINALIZE of the same job got there first (`out` is
// a finished store); then `partial`'s leftovers are removed.
absl::Status PublishFinishedStore(const std::filesystem::path& partial,
                                  const std::filesystem::path& out);

}  // namespace wavebake
