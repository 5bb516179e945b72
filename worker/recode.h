#pragma once
// Column-stage-only reruns on a kept trace. The staging array is the traced,
// row-transformed T (DESIGN.md §2); TRANSFORM_COLUMNS and FINALIZE only read
// it. So a store with other column parameters — mode, filter, target error,
// terms, bits, scaling, scope — comes from the same trace without tracing
// again: `bake --auto` tries several column targets per light resolution
// (driver/auto_bake.h) and the charts sweep dozens (bench/charts_data.cc).
#include <filesystem>

#include "absl/status/status.h"
#include "nlohmann/json.hpp"
#include "worker/bake_context.h"

namespace wavebake {

// Everything the staged values depend on: the scene (by hash) and the trace
// parameters (light resolution, layout, supersampling, seed, row filter,
// tiles and groups, the effective ray offset, refinement). BAKE_TILE's
// CreateStaging records it in staging/.zattrs.
nlohmann::json TraceRecord(const BakeContext& ctx);

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
