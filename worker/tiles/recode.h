#pragma once
// Column-stage-only reruns on a kept trace. The staging array is the traced,
// row-transformed T (DESIGN.md §2); TRANSFORM_COLUMNS and FINALIZE only read
// it. So a store with other column parameters — mode, filter, target error,
// terms, bits, scaling, scope — comes from the same trace without tracing
// again: `bake --auto` tries several column targets per light resolution
// (driver/bake/auto_bake.h) and the charts sweep dozens (bench/charts_data.cc).
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "nlohmann/json.hpp"
#include "worker/tiles/bake_context.h"

namespace wavebake {

// Everything the staged values depend on: the scene (by hash) and the trace
// parameters (the Stage::kTrace rows of core/bake/bake_param_table.h, with the
// effective ray offset). BAKE_TILE's
// CreateStaging records it in staging/.zattrs.
nlohmann::json TraceRecord(const BakeContext& ctx);

struct TraceOptions {
  int threads = 1;                            // BAKE_TILE tasks at a time
  const std::atomic<bool>* cancel = nullptr;  // raised: Cancelled, and nothing is left at `dir`
  // After each tile: tiles done, and the rays traced so far.
  std::function<void(int, uint64_t)> on_tile = {};
};

// The trace alone: BAKE_TILE × tiles into a new directory `dir` (root group
// and staging with its trace record, nothing else) — the input of Recode and
// of relighting the dense staged T (driver/relight/staged_relight.h). Returns the
// rays traced. `dir` must not exist (AlreadyExists); nothing is left there
// on failure.
absl::StatusOr<uint64_t> TraceStaging(const BakeContext& ctx, const std::filesystem::path& dir,
                                      const TraceOptions& options = {});

struct RecodeOptions {
  int threads = 1;  // TRANSFORM_COLUMNS tasks at a time
};

// Writes a complete store at `out` from the staging of `traced` (a store
// baked with keep_staging, or any staging directory with its trace record),
// coded with ctx's column parameters; `traced` is left as it was.
// FailedPrecondition naming the field when ctx's trace record differs from
// the staging's (or the staging has none or is incomplete); `out` must not
// exist (AlreadyExists). Nothing is left at `out` on failure.
absl::Status Recode(const BakeContext& ctx, const std::filesystem::path& traced,
                    const std::filesystem::path& out, const RecodeOptions& options = {});

}  // namespace wavebake
