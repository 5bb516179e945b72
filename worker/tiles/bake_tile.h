#pragma once
// BAKE_TILE, the map half of the bake (DESIGN.md §2): for one spatial tile,
// trace every sample's row of T (core/transport/transport_row.h), row-transform it
// (worker/tiles/row_transform.h), then transpose it group by group and write one
// staging chunk per column group, plus the tile's energy.
#include <cstdint>
#include <filesystem>

#include "absl/status/status.h"
#include "worker/loop/task_signals.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/memory_staging.h"

namespace wavebake {

// Counters that add up over tiles (the job's progress, DESIGN.md §4 Watch).
struct TileStats {
  uint64_t rays_traced = 0;    // occlusion rays handed to Embree
  uint64_t bytes_written = 0;  // compressed chunk bytes on disk (staging/transport + tile_energy)
  uint64_t samples = 0;        // non-masked cells of the tile
  uint64_t rows_reused = 0;    // of those, rows an update bake copied (worker/tiles/row_reuse.h)
};

// Writes chunks (g, tile) of staging/transport for every group g and chunk
// `tile` of staging/tile_energy (worker/tiles/staging.h; CreateStaging must have
// run: NotFound otherwise, FailedPrecondition if the arrays do not match the
// context's plan). Staged values are the row-transformed rows, albedo factored
// out; masked cells and the last group's padding rows are 0. The energy is
// Σ staged², summed in double in a fixed order and stored as float32.
//
// Memory: the tile's rows (tile_cells × M floats, worker/loop/task_buffer.h) and
// one chunk, never S×M; into an in-memory staging, a band of rows (about
// 4 MiB) at a time, transposed straight into the job's chunks. Single-threaded; tiles may run
// concurrently on one context, in any order, and a retried tile rewrites the same bytes: the chunks
// depend only on (context, tile). `tile` outside [0, plan.tiles()) is InvalidArgument naming
// "tile". stats (may be null) is added to. Between tile rows BakeTile
// checks signals.cancel (once it is true it returns Cancelled without
// writing, or abandoning the in-memory chunks it began: a worker whose lease
// was withdrawn stops promptly, DESIGN.md §4)
// and publishes its rays so far to signals.rays_traced.
//
// With `memory` (not null) and no kept staging, the staging/transport chunks
// go to the job's in-memory staging if it admits the job
// (worker/tiles/memory_staging.h); the tile's energy is written to the store
// either way.
absl::Status BakeTile(const BakeContext& ctx, const std::filesystem::path& store, int tile,
                      TileStats* stats, const TaskSignals& signals = {},
                      MemoryStaging* memory = nullptr);

}  // namespace wavebake
