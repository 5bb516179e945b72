#pragma once
// `wavebake bake` (DESIGN.md §5, "the embedded default"): a coordinator and
// N workers in this one process, talking through the coordinator's
// in-process channel with the same services, the same planner and the same
// worker loop as a cluster — so the cluster code is the code every bake runs.
// The coordinator's data directory is a temporary one beside the output,
// removed afterwards; the finished store is moved to the output.
#include <algorithm>
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>

#include "absl/status/statusor.h"
#include "coordinator/service/coordinator.h"
#include "coordinator/service/job_planner.h"
#include "core/bake/bake_params.h"
#include "driver/process/memory_limit.h"
#include "wavebake.pb.h"
#include "worker/columns/publish_store.h"  // ResolveOutputPath: OUT as a bake writes it

namespace wavebake::driver {

struct EmbeddedBakeOptions {
  int workers = 0;  // worker loops of one thread each; 0 = one per hardware thread
  // The job's events as driver/jobs/job_watch.h delivers them (progress, failures).
  std::function<void(const v1::JobEvent&)> on_event = {};
  // Raised (e.g. by SIGINT): the job is cancelled and the bake returns it CANCELLED.
  const std::atomic<bool>* interrupted = nullptr;
  // The in-process coordinator once it runs, with what its planner reads
  // scenes from; and (on_ending, on every way out after on_started) again
  // once the job has ended and the workers are gone, before the store is
  // published at `out` and the coordinator shuts down: `bake --serve` shows
  // it on the web monitor meanwhile. on_ending's job_id is empty when the
  // job was never submitted.
  std::function<void(Coordinator&, const PlannerOptions&)> on_started = {};
  std::function<void(Coordinator&, const std::string& job_id)> on_ending = {};
  // Staging chunks of a job whose whole staging fits this many bytes stay
  // in memory (worker/tiles/memory_staging.h) instead of going through the store;
  // 0: always the store. The peak memory of such a bake is up to this much
  // more than a store-staged one's (docs/RESULTS.md).
  uint64_t memory_staging_bytes = DefaultMemoryStagingBytes();
  // A quarter of what the process may use (driver/process/memory_limit.h),
  // at most kMemoryStagingCap. 1 GiB held the N = 64 bunny and spot but not
  // N = 128 (1.6 GB), whose staging zstd and files were a sixth of the
  // bake's CPU. Past a few GB, fresh pages cost more than the store's round
  // trip on VMs that hand free pages back to the host, like ours (~6 µs a
  // page): cubes-wall camera 256², N = 64 (6.4 GB of rows) took 39–42 s of
  // CPU in memory against 34–37 s through the store, where 1.6 and 3.2 GB in
  // memory took 7 % and 12 % less (docs/PIPELINE.md).
  static uint64_t DefaultMemoryStagingBytes() {
    return std::min(UsableMemoryBytes() / 4, kMemoryStagingCap);
  }
  static constexpr uint64_t kMemoryStagingCap = uint64_t{4} << 30;
};

// The job as it ended: DONE (the store is at `out`; an older store there is
// replaced), FAILED with its error, or CANCELLED — then nothing is at `out`
// (an older store stays). Errors: bad input before the job starts (a scene
// file that cannot be read, an output path that is not a store, a refused
// request), named by its field.
absl::StatusOr<v1::Job> EmbeddedBake(const std::string& scene, const BakeParams& params,
                                     const std::filesystem::path& out,
                                     const EmbeddedBakeOptions& options);

}  // namespace wavebake::driver
