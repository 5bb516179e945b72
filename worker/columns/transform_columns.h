#pragma once
// TRANSFORM_COLUMNS, the reduce half of the blocked transpose (DESIGN.md §2):
// one group of light columns, read from the staging chunk of every tile,
// assembled into W×H column images, transformed to their depth and selected
// (core/columns/column_coding.h), and written back to staging as the group's
// GroupResult (worker/columns/group_result.h) for FINALIZE. Free of scheduling: the
// embedded bake's workers and remote ones call it alike, in any order, any number of
// times (a retry rewrites the same bytes).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/bake/job_plan.h"
#include "core/columns/uncovered_fill.h"
#include "storage/zarr/zarr_array.h"
#include "worker/columns/group_result.h"
#include "worker/loop/task_signals.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/memory_staging.h"

namespace wavebake {

struct GroupStats {
  int columns = 0;
  uint64_t kept = 0;           // coefficients kept over the group's columns
  uint64_t staging_bytes = 0;  // float32 bytes of staging read (one chunk per tile)
  uint64_t bytes_written = 0;  // size of the group's result file (0: held in memory)
  int min_bits = 2;            // max over the group's columns of their --bits auto need
  int searched = 0;            // columns whose depth was searched (the others kept an old one)
};

// Memory: one group of column images (group_size × W×H floats) plus one
// staging chunk; never S×M. Errors: `group` out of range (InvalidArgument
// naming "group"); staging missing or of another plan (FailedPrecondition);
// Cancelled once signals.cancel is seen (checked between staging chunks and
// between columns; nothing is written then).
// With `memory`, the chunks the job's in-memory staging holds
// (worker/tiles/memory_staging.h) are read from there, the rest from the
// store; the group's result is held there for FINALIZE where the job is held
// and the result fits, else written to staging/groups.
// With `old` (an update's old coding of the group, its columns only), a
// column that KeepsItsDepth is coded at its old depth without the search.
absl::Status TransformColumns(const BakeContext& ctx, const std::filesystem::path& store, int group,
                              GroupStats* stats, const TaskSignals& signals = {},
                              MemoryStaging* memory = nullptr, const GroupResult* old = nullptr);

// Whether an update codes a column anew at its old depth (`was`) rather than
// searching again: an edit that leaves its energy within a quarter of the old
// one moves what the depths keep little, and the search is most of the
// coding's cost. The old depth still meets the budget (the selection is
// against it at any depth); it may keep more coefficients than the best one.
bool KeepsItsDepth(const ColumnCodingParams& p, const GroupColumn& was,
                   std::span<const float> column);

// The column images of `group`, assembled from chunk (group, t) of every
// tile, each read once: from the job's in-memory staging (`memory`) if it
// holds it, else from `staging`. Image k (the row-major W×H image
// images[k·W·H, (k+1)·W·H)) is the group's column columns[k], or column k
// when `columns` is empty (all of them).
absl::Status AssembleColumns(const JobPlan& plan, const ZarrArray& staging,
                             const MemoryStaging::Job* memory, int group, std::span<float> images,
                             GroupStats* stats, const TaskSignals& signals,
                             std::span<const int> columns = {});

// The fill of uncovered cells a column of ctx's layout is transformed with
// (only the uv layout fills, core/layouts/layout.h); none: they stay 0.
std::optional<CellFiller> UncoveredFiller(const BakeContext& ctx);

// E_ref of error scope "matrix": Σ staging/tile_energy / M, summed in tile
// order in double (the same number on every worker).
absl::StatusOr<double> ReadMatrixEnergy(const JobPlan& plan, const std::filesystem::path& store);

}  // namespace wavebake
