#pragma once
// How a bake is cut into tasks (DESIGN.md §2): BAKE_TILE per spatial tile,
// TRANSFORM_COLUMNS per column group, one FINALIZE. Pure arithmetic shared
// by the coordinator (to plan), the workers (to run) and the store layout.
#include <cstdint>

#include "core/bake/bake_params.h"

namespace wavebake {

struct TileRect {
  int x0 = 0, y0 = 0, width = 0, height = 0;  // cells of the W×H sample grid
};

// The staging array is [M, W*H] float32 chunked [group_size, tile_cells]: the
// chunk layout *is* the transpose. Its second axis enumerates grid cells tile
// by tile (tile t = ty*tiles_x + tx), row-major inside a tile, so chunk (g, t)
// holds exactly the columns of group g restricted to tile t.
// Columns per TRANSFORM_COLUMNS task when the parameters leave it to the
// plan (column_group 0): the most, a power of two up to kMaxAutoGroup, whose
// column images fit in kAutoGroupImageBytes. Every staging chunk and every
// group result is a file of its own, and creating a file is not cheap: 0.5–
// 0.9 ms of system time each on the ext4 the bakes were measured on
// (docs/RESULTS.md), against ~2 ms of coding work for a 1024-column chunk of
// a 32² tile. Larger groups mean fewer, larger files; the bound keeps two
// tasks' images well inside a 2 GiB worker (256 columns at 512² samples).
inline constexpr int kMaxAutoGroup = 1024;
inline constexpr int64_t kAutoGroupImageBytes = int64_t{256} << 20;
int AutoGroupSize(int columns, int cells);

struct JobPlan {
  int width = 0, height = 0;  // sample grid W×H
  int tile_w = 0, tile_h = 0;
  int tiles_x = 0, tiles_y = 0;
  int light_res = 0;   // N
  int columns = 0;     // M = 6 N² (cube) or N² (plane light domain)
  int group_size = 0;  // columns per TRANSFORM_COLUMNS task
  int groups = 0;
  // Diffuse bounces TRANSFORM_COLUMNS adds (BakeParams::bounces, `auto`
  // resolved; core/bake/bake_gather.h), and the auxiliary samples a camera
  // layout's bounces gather from: BAKE_TILE tasks tiles()..all_tiles()−1
  // trace their rows, tile_cells() at a time, into staging/aux_transport.
  int bounces = 0;
  int aux_samples = 0;

  int tiles() const { return tiles_x * tiles_y; }
  int aux_tiles() const { return (aux_samples + tile_cells() - 1) / tile_cells(); }
  // The bounce energies a store records (worker/columns/bounce_record.h):
  // Σ T_b² for b = 0..bounces, or with an auxiliary set its vertices' for
  // b = 0..bounces−1, the light its pixels gather.
  int bounce_energies() const { return aux_samples > 0 ? bounces : bounces + 1; }
  int all_tiles() const { return tiles() + aux_tiles(); }
  int tile_cells() const { return tile_w * tile_h; }
  TileRect Tile(int t) const {
    return {(t % tiles_x) * tile_w, (t / tiles_x) * tile_h, tile_w, tile_h};
  }
  // Column range [first, first+count) of group g.
  int GroupFirst(int g) const { return g * group_size; }
  int GroupCount(int g) const {
    const int rest = columns - g * group_size;
    return rest < group_size ? rest : group_size;
  }
  // Position of grid cell (x, y) on the staging array's second axis.
  int64_t StagingCell(int x, int y) const {
    const int t = (y / tile_h) * tiles_x + x / tile_w;
    return int64_t{t} * tile_cells() + (y % tile_h) * tile_w + x % tile_w;
  }
};

// width/height: the layout's grid (powers of two); p must be valid.
JobPlan MakeJobPlan(const BakeParams& p, int width, int height);

}  // namespace wavebake
