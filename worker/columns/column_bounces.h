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

// ctx.plan.bounces > 0: adds them to the group's column images (column c at
// images[c·W·H, (c+1)·W·H)) and writes the group's row of
// staging/bounce_energy (Σ T_b² over its columns, b = 0..B, or the auxiliary
// set's for b < B; worker/tiles/staging.h).
// A camera's auxiliary rows are read from `memory` where the job's
// in-memory staging holds them, else from staging/aux_transport.
// Memory: two column images beyond the group's. Cancelled once signals.cancel
// is seen (between columns; nothing is written then).
absl::Status AddGroupBounces(const BakeContext& ctx, const std::filesystem::path& store, int group,
                             std::span<float> images, const TaskSignals& signals,
                             const MemoryStaging::Job* memory = nullptr);

}  // namespace wavebake
