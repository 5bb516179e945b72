#pragma once
// Row reuse of an update bake (`bake NEW --update OLD.wbk`): the staged rows
// of an old store (baked with --keep-staging) are copied into the new bake's
// BAKE_TILE wherever the edit cannot reach them, and only the other rows are
// traced (Boulton §4.5: rebuild only the transfer functions a change reaches).
//
// A row depends on its sample (position, normal), the ray offset ε, the
// shared jitter pattern and the visibility of the pattern's rays
// (core/transport/dirty_rows.h). A new sample takes the row of an old
// sample with bit-identical position and normal (whatever cell either sits
// in: a hilbert layout re-sorts when a mesh moves) unless one of its rays may
// see the changed geometry; with the same parameters the copied row is the
// bits a full bake would trace, so the column stage run from the merged rows
// gives a store byte-identical to a full bake of the new scene.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "core/bake/job_plan.h"
#include "core/transport/dirty_rows.h"
#include "nlohmann/json.hpp"
#include "worker/tiles/changed_columns.h"

namespace wavebake {

struct BakeContext;
class SceneFiles;

// Where an update's old store and its scene are on this machine.
struct OldStore {
  std::filesystem::path path;
  // What the new store's update record names it by: the path for a local
  // bake, the store's name under the store root for a coordinator's job.
  std::string recorded;
  // The old scene as LoadScene reads it here (a coordinator's update_scene,
  // resolved as a job's scene is) and the files it may read; empty: the scene
  // the store names (storage/store/store_scene.h LocateStoreScene).
  std::string scene;
  std::shared_ptr<const SceneFiles> scene_files;
};

struct RowReuse {
  std::filesystem::path old_store;
  std::string from;    // OldStore::recorded
  bool exact = false;  // --update-exact: the whole column stage runs from the merged rows
  // Per cell of the new grid (y·W + x): the old staging array's column
  // (JobPlan::StagingCell of the old cell) holding its row, or -1: traced.
  std::vector<int64_t> source;
  // Every reused row sits in the cell it had (camera layouts, a kept
  // hilbert layout): the column images differ from the old ones only in
  // the tiles marked in tile_touched (a rebaked cell, or one masked in one
  // store and not in the other), so --update can recompute only the columns
  // those tiles change (worker/columns/local_columns.h).
  bool in_place = false;
  // --update only (not exact), diffuse rows on the cube: a matched sample
  // the edit reaches is patched instead of traced: its old row plus the
  // row transform of DirtyRowTest::RowDelta (the brute-force difference over
  // the rays that see the change). patch[cell] = 1 for those; empty if none.
  std::vector<uint8_t> patch;
  std::shared_ptr<const DirtyRowTest> delta;
  int64_t patched = 0;
  bool kept_layout = false;           // the hilbert cells are the old store's
  std::vector<uint8_t> tile_touched;  // per tile of the plan
  int64_t samples = 0, reused = 0, rebaked = 0;
  int64_t unmatched = 0;  // rebaked because no old sample had its position and normal
  // Non-empty when nothing could be reused, and why (a moved camera, another ε).
  std::string full_reason;
  std::vector<std::string> changed_meshes;  // names: removed/added (old and new placement)
  std::vector<std::string> albedo_meshes;   // names whose albedo alone changed
  DirtyRowStats dirty;
  double plan_seconds = 0;

  // The "update" object of the new store's .zattrs.
  nlohmann::json Record() const;
};

// Whether `old_store` can seed an update bake with `params`: a finished
// store (FailedPrecondition naming --update otherwise) that kept its staged
// rows and their trace record (else: bake it with --keep-staging), baked
// with the same parameters (else the first one that differs, by name).
// Reads only.
absl::Status CheckUpdateSource(const std::filesystem::path& old_store, const BakeParams& params);

// Whether the scene `old_store` names still loads here and hashes as the
// store recorded it (PlanRowReuse needs it: FailedPrecondition naming the
// scene otherwise). For a local update, which can say so before any task
// runs; a coordinator's job brings the old scene with it instead.
absl::Status CheckOldScene(const std::filesystem::path& old_store);

// The reuse plan of ctx (the new scene's context) from `old_store`: checks
// it (CheckUpdateSource), loads the old store's scene (it must still hash as
// recorded: the old placement of what moved bounds the dirty rows), diffs the
// scenes (core/scene/scene_diff.h) and runs the dirty-row test on every
// matched sample. Reads only.
//
// For --update (not exact) on a hilbert layout, ctx.samples.grid is first
// replaced by the old store's cells when every mesh has a counterpart of the
// same vertex count (unchanged, or moved: same name): the samples of a moved
// mesh stay in their old cells instead of re-sorting the whole curve, so
// the reused rows stay in place and the columns can be kept
// (worker/columns/local_columns.h). The store's layout then is the old one.
absl::StatusOr<std::shared_ptr<const RowReuse>> PlanRowReuse(BakeContext& ctx, const OldStore& old,
                                                             bool exact);

// Copies the old rows of tile `tile`'s reused cells into `rows` (cell c of
// the tile at c·stride, plan.columns values, as BAKE_TILE lays them out) and
// sets filled[c] = 1 for them, 2 for those to patch (PatchRow), 0 for the
// others. Returns how many. With `rewritten` (reuse.in_place only: each old
// row is in its old cell), also the old rows of the cells filled 0, from
// the same chunks (worker/tiles/changed_columns.h).
absl::StatusOr<int> FillReusedRows(const RowReuse& reuse, const JobPlan& plan, int tile,
                                   std::span<float> rows, size_t stride,
                                   std::vector<uint8_t>& filled, OldRows* rewritten = nullptr);

// Adds the change's difference to the old row of sample `id` (filled 2),
// setting changed[m] = 1 where value m's bits change (if `changed` is given:
// one byte per column).
void PatchRow(const RowReuse& reuse, const BakeContext& ctx, int32_t id, std::span<float> row,
              std::span<uint8_t> changed = {});

// Whether an update's TRANSFORM_COLUMNS (worker/columns/local_columns.h) codes only the columns its
// tiles changed: --update (not exact) of a bake without bounces. Bounced light reaches every sample
// wherever the edit is (the gather spans the scene, T = Σ_b G^b T₀), so with bounces every column
// is coded anew from the updated direct rows and the new scene's gather, each column at its old
// depth unless its energy moved (worker/columns/transform_columns.h KeepsItsDepth).
bool CodesChangedColumnsOnly(const BakeContext& ctx);

// Whether TRANSFORM_COLUMNS starts from the old store's codings
// (worker/columns/local_columns.h): --update, not exact, with or without bounces.
bool StartsFromOldCodings(const BakeContext& ctx);

// Adds reuse.Record() as "update" to the store's root .zattrs (after
// FINALIZE), with the columns coded anew out of `columns`, how many of
// those were searched for their depth, and the bake's bounce count.
absl::Status WriteUpdateRecord(const std::filesystem::path& store, const RowReuse& reuse,
                               int64_t columns_recomputed, int64_t columns_searched,
                               int64_t columns, int bounces);

}  // namespace wavebake
