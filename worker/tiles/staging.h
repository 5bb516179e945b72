#pragma once
// The staging arrays of a running job (DESIGN.md §2 "the blocked transpose",
// storage/store/store_layout.h): BAKE_TILE writes them, TRANSFORM_COLUMNS reads
// them, FINALIZE drops them.
#include <filesystem>

#include "absl/status/status.h"
#include "core/bake/job_plan.h"
#include "nlohmann/json.hpp"
#include "storage/zarr/array_spec.h"

namespace wavebake {

// staging/transport: float32 [M, W*H] chunked [group_size, tile_cells], fill
// 0. Chunk (g, t) holds columns GroupFirst(g).. of group g over the cells of
// tile t (tile-major second axis, JobPlan::StagingCell); the last group's
// chunks are padded with zero rows.
ArraySpec StagingTransportSpec(const JobPlan& plan);
// staging/tile_energy: float32 [tiles] chunked [1], fill 0: Σ of the squared
// staged values of each tile.
ArraySpec TileEnergySpec(const JobPlan& plan);

// staging/aux_transport (plan.aux_samples > 0): as staging/transport over
// the auxiliary samples (core/bake/bake_gather.h), aux tile a holding samples
// a·tile_cells.. (the last one padded with zero rows): [M, aux_tiles·tile_cells].
ArraySpec AuxTransportSpec(const JobPlan& plan);

// staging/bounce_energy (plan.bounces > 0): float32 [groups, E] chunked
// [1, E], E = plan.bounce_energies(), fill 0: row g holds the energies of
// group g's columns, written by TRANSFORM_COLUMNS, summed by FINALIZE.
ArraySpec BounceEnergySpec(const JobPlan& plan);

// Creates the store's root group, the staging group and both arrays, and,
// given one, writes `trace` (worker/tiles/recode.h TraceRecord: what the staged
// values depend on) as the staging group's attributes, so that a kept
// staging can be recoded later. Idempotent: several workers (or a retried
// task) may call it, concurrently too; arrays already there with the same
// spec are kept with their chunks. A staging array with another spec
// (another plan) is AlreadyExists.
absl::Status CreateStaging(const JobPlan& plan, const std::filesystem::path& store,
                           const nlohmann::json& trace = nullptr);

}  // namespace wavebake
