#pragma once
// The bounces of TRANSFORM_COLUMNS (worker/columns/transform_columns.h): one call
// between assembling a group's column images and coding them. T_b = G T_{b−1}
// (core/transport/bounce_gather.h) acts on the spatial index only, so a
// column image of row-transformed T₀ becomes the same column of the
// row-transformed T = T₀ + … + T_B in place, before the column transform.
#include <filesystem>
#include <span>

#include "absl/status/status.h"
#include "worker/loop/task_signals.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/memory_staging.h"

namespace wavebake {

// Bounced light a column may leave out. The gather's sum Σ_b T_b is added to
// every column image but those where it holds at most `threshold` of energy:
// those keep their direct light alone, and left_out[c] (per column of the
// group) receives that energy, which CodeColumn spends from the column's
// budget (core/columns/column_coding.h), so the error target keeps its
// meaning. TransformColumns sets the threshold to kBounceShare of the
// column's budget target²·E_ref under the default matrix-scoped error, and
// to 0 (only a bounce of exactly nothing left out) under --error-scope column
// and --column-terms, which have no budget to spend it from. The weak bounces
// are many: of cubes-wall's camera's 6144 columns (128², N = 32, one bounce)
// 3541 hold less than a quarter of their budget, 1.8 % of the matrix's budget
// together, and, dense where the direct light was sparse, cost the coding
// most of its time.
struct BounceTruncation {
  double threshold = 0;
  std::span<double> left_out;
};
inline constexpr double kBounceShare = 0.25;

// ctx.plan.bounces > 0: adds them to the group's column images (column c at
// images[c·W·H, (c+1)·W·H)) as `truncation` says and writes the group's row of
// staging/bounce_energy (Σ T_b² over its columns, b = 0..B, or the auxiliary
// set's for b < B, whether added or left out; worker/tiles/staging.h).
// A camera's auxiliary rows are read from `memory` where the job's
// in-memory staging holds them, else from staging/aux_transport.
// Memory: two column images beyond the group's. Cancelled once signals.cancel
// is seen (between columns; nothing is written then).
absl::Status AddGroupBounces(const BakeContext& ctx, const std::filesystem::path& store, int group,
                             std::span<float> images, const BounceTruncation& truncation,
                             const TaskSignals& signals,
                             const MemoryStaging::Job* memory = nullptr);

}  // namespace wavebake
