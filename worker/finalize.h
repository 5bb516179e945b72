#pragma once
// FINALIZE (DESIGN.md §2): the groups' coded columns (worker/group_result.h)
// become the store's CSC arrays, samples/* and the manifest (DESIGN.md §3),
// then staging is dropped. Quantization happens here because the steps are a
// matrix-wide choice (core/columns/quantization_steps.h): each group recorded, per
// column, max_i |v_i/k_i| and the expected dither energy per unit step;
// FINALIZE picks every column's step Δ_c (stored as `scale`) and quantizes.
//
// Memory: a few groups' coded columns (threads + 1) plus O(M) column arrays,
// never S×M.
// Idempotent: a retry rewrites the same bytes, and a retry after staging was
// dropped finds the finished manifest and succeeds without work.
#include <atomic>
#include <filesystem>

#include "absl/status/status.h"
#include "worker/bake_context.h"
#include "worker/memory_staging.h"

namespace wavebake {

struct FinalizeOptions {
  bool keep_staging = false;
  // Raised: stop between two groups with CANCELLED (a cancelled job; a large
  // store's FINALIZE runs far longer than the bound on ending a bake).
  const std::atomic<bool>* cancel = nullptr;
  // Threads reading and quantizing groups (0: one per hardware thread).
  // FINALIZE runs alone at the end of a job; the stores do not depend on it.
  int threads = 0;
  // The job's in-memory staging chunks (worker/memory_staging.h), if any,
  // are dropped with staging.
  MemoryStaging* memory = nullptr;
};

absl::Status Finalize(const BakeContext& ctx, const std::filesystem::path& store,
                      const FinalizeOptions& options);

// Removes staging/ from a store (atomically renamed away first). Symbolic
// links in it are removed, not followed. OK if there is none.
absl::Status DropStaging(const std::filesystem::path& store);

}  // namespace wavebake
