#include "worker/columns/local_columns.h"

#include <algorithm>
#include <fstream>
#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/columns/column_coding.h"
#include "storage/files/atomic_file.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"
#include "worker/columns/group_result.h"
#include "worker/columns/transform_columns.h"
#include "worker/loop/task_buffer.h"
#include "worker/tiles/row_reuse.h"

namespace wavebake {
namespace {

std::filesystem::path CountPath(const std::filesystem::path& store, int group) {
  return GroupResultDir(store) / absl::StrCat(group, ".recomputed");
}

absl::Status WriteCount(const std::filesystem::path& store, int group, RecodedColumns count) {
  const std::string text = absl::StrCat(count.recomputed, " ", count.searched);
  return AtomicWriteFile(CountPath(store, group), std::as_bytes(std::span(text)));
}

bool Stopped(const TaskSignals& signals) {
  return signals.cancel != nullptr && signals.cancel->load(std::memory_order_relaxed);
}

// The group's columns whose values differ from the old store's, from the
// records of the touched tiles (RowReuse::tile_touched; every row of the
// others is an old row in its old cell: the same bits). NotFound if a
// touched tile left none.
absl::StatusOr<std::vector<uint8_t>> ChangedInGroup(const RowReuse& reuse, const JobPlan& plan,
                                                    const std::filesystem::path& store, int group) {
  std::vector<uint8_t> changed(plan.GroupCount(group), 0);
  for (int t = 0; t < plan.tiles(); ++t) {
    if (!reuse.tile_touched[t]) continue;
    if (absl::Status s = OrChangedColumns(store, t, plan.GroupFirst(group), changed); !s.ok())
      return s;
  }
  return changed;
}

// The old coding of column j of `was`, appended to `result` as it was.
void KeepColumn(const GroupResult& was, int j, size_t at, std::optional<double> matrix_energy,
                GroupResult* result) {
  GroupColumn kept = was.columns[j];
  if (matrix_energy) kept.reference_energy = *matrix_energy;
  result->columns.push_back(kept);
  result->positions.insert(result->positions.end(), was.positions.begin() + at,
                           was.positions.begin() + at + kept.kept);
  result->values.insert(result->values.end(), was.values.begin() + at,
                        was.values.begin() + at + kept.kept);
}

// Every column of the group coded anew, each at its old depth in `old`
// where KeepsItsDepth (none: all searched).
absl::Status CodeWholeGroup(const BakeContext& ctx, const std::filesystem::path& store, int group,
                            const GroupResult* old, GroupStats* stats, const TaskSignals& signals) {
  GroupStats local;
  if (absl::Status s = TransformColumns(ctx, store, group, &local, signals, nullptr, old); !s.ok())
    return s;
  if (stats) *stats = local;
  return WriteCount(store, group, {local.columns, local.searched});
}

}  // namespace

absl::Status LocalTransformColumns(const BakeContext& ctx, const std::filesystem::path& store,
                                   int group, GroupStats* stats, const TaskSignals& signals) {
  const JobPlan& plan = ctx.plan;
  const RowReuse* reuse = ctx.reuse.get();
  if (!CodesChangedColumnsOnly(ctx)) {
    // With bounces every column changes (bounced light reaches every
    // sample). The old store was baked with the same parameters, bounces
    // included, so its column energies are of the same sum T = Σ_b G^b T₀.
    absl::StatusOr<GroupResult> old =
        reuse ? ReadGroupColumns(reuse->old_store, group) : absl::NotFoundError("not an update");
    return CodeWholeGroup(ctx, store, group, old.ok() ? &*old : nullptr, stats, signals);
  }
  absl::StatusOr<GroupResult> old_result =
      reuse && reuse->in_place && reuse->full_reason.empty()
          ? ReadGroupResult(reuse->old_store, group)
          : absl::StatusOr<GroupResult>(absl::NotFoundError("rows moved"));
  absl::StatusOr<std::vector<uint8_t>> changed =
      old_result.ok() ? ChangedInGroup(*reuse, plan, store, group) : old_result.status();
  if (!changed.ok() || old_result->first_column != plan.GroupFirst(group) ||
      static_cast<int>(old_result->columns.size()) != plan.GroupCount(group)) {
    return CodeWholeGroup(ctx, store, group, nullptr, stats, signals);
  }
  absl::StatusOr<ZarrArray> now = ZarrArray::Open(store::Path(store, store::kStagingTransport));
  if (!now.ok()) return now.status();
  absl::StatusOr<double> matrix_energy = ReadMatrixEnergy(plan, store);
  if (!matrix_energy.ok()) return matrix_energy.status();
  // The images of the changed columns only; a group without any reads no chunk.
  std::vector<int> recode;
  for (int j = 0; j < plan.GroupCount(group); ++j)
    if ((*changed)[j]) recode.push_back(j);
  const size_t image = size_t(plan.width) * plan.height;
  // Asked at the group's full size: the thread's buffer then holds any later
  // group's changed columns without a new mapping, whose pages would all be
  // faulted in (and zeroed) again. Only the pages written are touched.
  const std::span<float> images =
      TaskBuffer(size_t(plan.GroupCount(group)) * image).first(recode.size() * image);
  GroupStats local;
  if (!recode.empty())
    if (absl::Status s =
            AssembleColumns(plan, *now, nullptr, group, images, &local, signals, recode);
        !s.ok())
      return s;

  ColumnCodingParams params =
      MakeColumnCodingParams(ctx.params, plan.width, plan.height, *matrix_energy);
  const std::optional<CellFiller> filler = UncoveredFiller(ctx);
  if (filler) params.filler = &*filler;
  GroupResult result;
  result.group = group;
  result.first_column = plan.GroupFirst(group);
  result.matrix_energy = *matrix_energy;
  const std::optional<double> reference =
      ctx.params.error_scope == ErrorScope::kMatrix ? std::optional(*matrix_energy) : std::nullopt;
  size_t searched = 0, at = 0, k = 0;  // at: start of the old column's slice
  CodedColumn coded;
  for (int j = 0; j < plan.GroupCount(group); ++j) {
    if (Stopped(signals)) return absl::CancelledError(absl::StrCat("group ", group, ": cancelled"));
    const GroupColumn& was = old_result->columns[j];
    if ((*changed)[j]) {
      const std::span<const float> column = images.subspan(k++ * image, image);
      if (KeepsItsDepth(params, was, column)) {
        CodeColumnAtDepth(params, column, was.depth, &coded);
      } else {
        ++searched;
        CodeColumn(params, column, &coded);
      }
      AppendColumn(coded, &result);
    } else {
      KeepColumn(*old_result, j, at, reference, &result);
    }
    local.min_bits = std::max<int>(local.min_bits, result.columns.back().min_bits);
    at += was.kept;
  }
  if (absl::Status s = WriteGroupResult(store, result); !s.ok()) return s;
  local.columns = plan.GroupCount(group);
  local.kept = result.positions.size();
  std::error_code ec;
  local.bytes_written = std::filesystem::file_size(GroupResultPath(store, group), ec);
  if (stats) *stats = local;
  return WriteCount(store, group, {int64_t(recode.size()), int64_t(searched)});
}

absl::StatusOr<RecodedColumns> RecomputedColumns(const JobPlan& plan,
                                                 const std::filesystem::path& store) {
  RecodedColumns total;
  for (int g = 0; g < plan.groups; ++g) {
    RecodedColumns n{-1, -1};
    {
      std::ifstream in(CountPath(store, g));
      if (!(in >> n.recomputed >> n.searched) || n.recomputed < 0 || n.searched < 0)
        n = {plan.GroupCount(g), plan.GroupCount(g)};
    }
    total.recomputed += n.recomputed;
    total.searched += n.searched;
    // Read once, by FINALIZE: a kept staging holds a full bake's files only.
    std::error_code ec;
    std::filesystem::remove(CountPath(store, g), ec);
  }
  RemoveChangedColumns(store);
  return total;
}

}  // namespace wavebake
