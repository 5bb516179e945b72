#pragma once
// FINALIZE (DESIGN.md §2): the groups' coded columns (worker/columns/group_result.h)
// become the store's CSC arrays, samples/* and the manifest (DESIGN.md §3),
// then staging is dropped. It runs as several tasks (core/bake/finalize_shards.h):
// shards that write the nnz-long arrays' chunks, each on its own worker, and
// a last task that writes the column arrays and the manifest. Quantization happens here because the
// steps are a matrix-wide choice (core/columns/quantization_steps.h): each group recorded, per
// column, max_i |v_i/k_i| and the expected dither energy per unit step; FINALIZE picks every
// column's step Δ_c (stored as `scale`) and quantizes.
//
// Memory: a few groups' coded columns (threads + 1) plus O(M) column arrays,
// never S×M; each task reads every group's column table (O(M)).
// Idempotent: a retry rewrites the same bytes, and a retry after staging was
// dropped finds the finished manifest and succeeds without work.
#include <atomic>
#include <filesystem>

#include "absl/status/status.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/memory_staging.h"

namespace wavebake {

struct FinalizeOptions {
  bool keep_staging = false;
  // Raised: stop between two groups with CANCELLED (a cancelled job; a large
  // store's FINALIZE runs far longer than the bound on ending a bake).
  const std::atomic<bool>* cancel = nullptr;
  // Threads reading and quantizing groups; the stores do not depend on it.
  // A worker passes its --threads (the CPUs of its Slurm step or pod: the
  // host's count would oversubscribe them); 0, for local callers such as
  // `wavebake recode`, is one per hardware thread.
  int threads = 0;
  // The job's in-memory staging (worker/tiles/memory_staging.h), if any:
  // group results held there are read from it, and it is dropped with
  // staging.
  MemoryStaging* memory = nullptr;
};

// The whole of FINALIZE in one call: every shard, then the last task
// (`wavebake recode`, tests). A worker runs them as separate tasks:
absl::Status Finalize(const BakeContext& ctx, const std::filesystem::path& store,
                      const FinalizeOptions& options);

// FINALIZE task `shard` < FinalizeShards(groups) (core/bake/finalize_shards.h):
// the chunks of transport/indices and data whose first element lies in the
// shard's groups (reading the groups after them a chunk's end needs), and
// the quantization outcome of the shard's columns. Its chunks are the bytes
// the one-task FINALIZE wrote: the codes of a column depend on its step and
// index only. OK without work when the store is already finished.
absl::Status FinalizeShard(const BakeContext& ctx, const std::filesystem::path& store, int shard,
                           const FinalizeOptions& options);

// The last FINALIZE task, once every shard is done: indptr, depth, scale,
// samples, the stats and the manifest, then staging is dropped.
// FailedPrecondition naming a shard that has not finished.
absl::Status FinalizeStore(const BakeContext& ctx, const std::filesystem::path& store,
                           const FinalizeOptions& options);

// Removes staging/ from a store (atomically renamed away first). Symbolic
// links in it are removed, not followed. OK if there is none.
absl::Status DropStaging(const std::filesystem::path& store);

}  // namespace wavebake
