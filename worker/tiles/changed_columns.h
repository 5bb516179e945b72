#pragma once
// Which columns a tile of an in-place `--update` changes (Boulton §4.5: a
// change reaches only the coefficients whose support covers it). BAKE_TILE
// has both the tile's old rows (it copies the reused ones from the old
// store) and its new ones, so it compares them there and records the
// columns that differ; TRANSFORM_COLUMNS (worker/columns/local_columns.h)
// then reads no old chunk to learn what to recode, and a group no tile
// changed reads no chunk at all.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/bake/job_plan.h"

namespace wavebake {

// The old staged rows of the cells of one tile that an in-place update
// traces, or masks in one of the two stores (a patched row's change is
// seen as it is patched: worker/tiles/row_reuse.h PatchRow).
struct OldRows {
  std::vector<int> cells;     // cells of the tile (c = cy·width + cx), increasing
  std::vector<float> values;  // row k (plan.columns values) is the old row of cells[k]
};

// Sets changed[m] = 1 (one byte per column of the plan) where the new row
// of a cell of `old` (cell c at rows[c·stride]) differs from its old one in
// any bit.
void OrChangedColumns(const OldRows& old, std::span<const float> rows, size_t stride,
                      std::span<uint8_t> changed);

// staging/changed/<tile>: the columns tile `tile` changed, one bit each
// (written whole or not at all).
absl::Status WriteChangedColumns(const std::filesystem::path& store, int tile,
                                 std::span<const uint8_t> changed);

// ORs into changed[j] the record of `tile` for columns first + j, j <
// changed.size(). NotFound if the tile wrote none.
absl::Status OrChangedColumns(const std::filesystem::path& store, int tile, int first,
                              std::span<uint8_t> changed);

// Removes the records (read by TRANSFORM_COLUMNS; a kept staging holds only
// what a full bake's does).
void RemoveChangedColumns(const std::filesystem::path& store);

}  // namespace wavebake
