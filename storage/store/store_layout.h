#pragma once
// Names inside a wavebake store (DESIGN.md §3) — the one place that spells
// them. A store is a Zarr v2 group; while a job runs, its staging arrays live
// under staging/ in the same format.
#include <filesystem>

namespace wavebake::store {

// "wavebake/2": `scale` is each column's quantization step and values decode
// as (q − u)·scale·2^(−s·l) (core/columns/quantizer.h); "/1" divided by 2^(bits−1)−1.
inline constexpr char kFormat[] = "wavebake/2";

// Final arrays.
inline constexpr char kTransport[] = "transport";        // group, attrs: encoding-type csc_matrix
inline constexpr char kIndptr[] = "transport/indptr";    // int64  [M+1]
inline constexpr char kIndices[] = "transport/indices";  // uint32 [nnz]  y*W+x in the Mallat layout
inline constexpr char kData[] = "transport/data";        // int16  [nnz]
inline constexpr char kDepth[] = "transport/depth";      // uint8  [M]
inline constexpr char kScale[] = "transport/scale";      // float32 [M]  quantization step
inline constexpr char kSamples[] = "samples";
inline constexpr char kGrid[] = "samples/grid";          // int32 [H, W]
inline constexpr char kPosition[] = "samples/position";  // float32 [S, 3]
inline constexpr char kNormal[] = "samples/normal";      // float32 [S, 3]
inline constexpr char kAlbedo[] = "samples/albedo";      // float32 [S, 3]
inline constexpr char kVertex[] = "samples/vertex";      // int32 [S] (mesh layouts)
// uv layouts (core/layouts/uv_atlas.h): per mesh, its texel rectangle x, y, width,
// height (row 0 at the top) and the UV domain u0, v0, u1, v1 that fills it.
inline constexpr char kUvRects[] = "samples/uv_rects";      // int32 [meshes, 4]
inline constexpr char kUvDomains[] = "samples/uv_domains";  // float32 [meshes, 4]

// Staging (removed by FINALIZE unless --keep-staging).
inline constexpr char kStaging[] = "staging";
// float32 [M, W*H] chunked [group_size, tile_cells]: the chunk layout is the
// transpose; the second axis is tile-major (core/bake/job_plan.h StagingCell).
inline constexpr char kStagingTransport[] = "staging/transport";
// float32 [tiles] chunked [1]: Σ of squared staged values of each tile (the
// matrix energy is needed by the "matrix" error scope before any group runs).
inline constexpr char kStagingTileEnergy[] = "staging/tile_energy";
// float32 [groups, bounces+1] chunked [1, bounces+1] (bounces > 0 only): Σ T_b²
// over each group's columns for b = 0..bounces (worker/columns/transform_columns.h).
inline constexpr char kStagingBounceEnergy[] = "staging/bounce_energy";
// float32 [M, aux_tiles·tile_cells] chunked [group_size, tile_cells] (camera
// layouts with bounces only): the direct rows of the auxiliary samples the
// bounces gather from (worker/tiles/staging.h).
inline constexpr char kStagingAuxTransport[] = "staging/aux_transport";
// Not Zarr: one <g>.wbg file per TRANSFORM_COLUMNS group (worker/columns/group_result.h).
inline constexpr char kStagingGroups[] = "staging/groups";
// Not Zarr: one <t> file per BAKE_TILE of an in-place --update, a bit per
// column the tile changed (worker/tiles/changed_columns.h).
inline constexpr char kStagingChanged[] = "staging/changed";
// Not Zarr: one <k>.wbq file per FINALIZE shard, its columns' quantization
// outcome for the last task (worker/columns/finalize_parts.h).
inline constexpr char kStagingFinalize[] = "staging/finalize";

inline std::filesystem::path Path(const std::filesystem::path& store, const char* name) {
  return store / name;
}

}  // namespace wavebake::store
