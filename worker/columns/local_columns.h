#pragma once
// TRANSFORM_COLUMNS of an `--update` bake (not --update-exact): only the
// columns the edit changed are transformed again (Boulton §4.5: Haar's local
// support). A column image is W×H staged values; when every reused row sits
// in its old cell (RowReuse::in_place), a column whose values in the tiles
// with a rebaked cell are bit-identical to the old store's (as BAKE_TILE
// recorded them: worker/tiles/changed_columns.h) is the same image, so its
// old coded column (the old store's kept staging/groups) is exact and is
// kept; the others are coded anew from the merged staging.
//
// How depth and quantization are decided then: a recomputed column is
// selected against the budget of the new matrix energy
// (core/columns/column_coding.h) at its old depth, unless it kept nothing
// before or its energy moved by over a quarter: then the adaptive depth
// search runs. The search is most of a column's coding; an edit that moves
// little of a column's energy moves its best depth little, and any depth
// meets the budget, so keeping the old one costs bytes at most, never
// error. A kept column keeps its depth and its selection (made against the
// old matrix energy, which a small edit moves little; its reference energy
// is set to the new one so FINALIZE budgets it as the others); the
// quantization step stays matrix-wide, planned by FINALIZE over all columns
// as in any bake. So the store differs from a full bake by the selections
// of kept columns and the depths of recomputed ones.
#include <filesystem>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "worker/columns/transform_columns.h"
#include "worker/loop/task_signals.h"
#include "worker/tiles/bake_context.h"

namespace wavebake {

// TransformColumns of group `group` for ctx (StartsFromOldCodings). With
// bounces every column is coded, at its old depth where KeepsItsDepth.
// Without, falls back to TransformColumns when the rows moved between cells, the old
// store kept no group result for the group, or a touched tile left no record. Writes how many
// columns were coded anew, and how many of those were searched for their depth, beside the group
// result (RecomputedColumns reads it).
absl::Status LocalTransformColumns(const BakeContext& ctx, const std::filesystem::path& store,
                                   int group, GroupStats* stats, const TaskSignals& signals = {});

struct RecodedColumns {
  int64_t recomputed = 0;  // coded anew (the others kept their old coding)
  int64_t searched = 0;    // of those, searched for their depth (the others kept theirs)
};

// Σ over groups of the columns LocalTransformColumns coded anew (a group
// without its counts: all its columns, all searched), removing the counts
// (FINALIZE reads them once, so that a kept staging holds only what a full
// bake's does).
absl::StatusOr<RecodedColumns> RecomputedColumns(const JobPlan& plan,
                                                 const std::filesystem::path& store);

}  // namespace wavebake
