#include "worker/columns/local_columns.h"

#include <algorithm>
#include <cstring>
#include <fstream>
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

absl::Status WriteCount(const std::filesystem::path& store, int group, size_t count) {
  const std::string text = std::to_string(count);
  return AtomicWriteFile(CountPath(store, group), std::as_bytes(std::span(text)));
}

bool Stopped(const TaskSignals& signals) {
  return signals.cancel != nullptr && signals.cancel->load(std::memory_order_relaxed);
}

}  // namespace

absl::Status LocalTransformColumns(const BakeContext& ctx, const std::filesystem::path& store,
                                   int group, GroupStats* stats, const TaskSignals& signals) {
  const JobPlan& plan = ctx.plan;
  const RowReuse* reuse = ctx.reuse.get();
  absl::StatusOr<GroupResult> old_result =
      reuse && reuse->in_place && reuse->full_reason.empty()
          ? ReadGroupResult(reuse->old_store, group)
          : absl::StatusOr<GroupResult>(absl::NotFoundError("rows moved"));
  if (!old_result.ok() || old_result->first_column != plan.GroupFirst(group) ||
      static_cast<int>(old_result->columns.size()) != plan.GroupCount(group)) {
    if (absl::Status s = TransformColumns(ctx, store, group, stats, signals); !s.ok()) return s;
    return WriteCount(store, group, plan.GroupCount(group));
  }
  absl::StatusOr<ZarrArray> now = ZarrArray::Open(store::Path(store, store::kStagingTransport));
  if (!now.ok()) return now.status();
  absl::StatusOr<ZarrArray> old =
      ZarrArray::Open(store::Path(reuse->old_store, store::kStagingTransport));
  if (!old.ok()) return old.status();
  absl::StatusOr<double> matrix_energy = ReadMatrixEnergy(plan, store);
  if (!matrix_energy.ok()) return matrix_energy.status();
  // The group's column images, each new chunk read once; in a touched tile
  // (RowReuse::tile_touched) the old chunk too, to find the columns whose
  // values differ from the old store's. Every row of an untouched tile was
  // copied in place: the same bits.
  const int count = plan.GroupCount(group);
  const size_t image = size_t(plan.width) * plan.height, cells = plan.tile_cells();
  const std::span<float> images = TaskBuffer(count * image);
  std::vector<uint8_t> changed(count, 0);
  std::vector<float> was_chunk;
  auto compare = [&](int t, std::span<const float> chunk) {
    if (!reuse->tile_touched[t]) return absl::OkStatus();
    was_chunk.resize(chunk.size());
    const int64_t index[] = {group, t};
    if (absl::Status s = old->ReadChunkInto(index, std::as_writable_bytes(std::span(was_chunk)));
        !s.ok())
      return s;
    for (int j = 0; j < count; ++j)
      changed[j] |= std::memcmp(chunk.data() + j * cells, was_chunk.data() + j * cells,
                                cells * sizeof(float)) != 0;
    return absl::OkStatus();
  };
  GroupStats local;
  if (absl::Status s =
          AssembleColumns(plan, *now, nullptr, group, images, &local, signals, compare);
      !s.ok())
    return s;

  const ColumnCodingParams params =
      MakeColumnCodingParams(ctx.params, plan.width, plan.height, *matrix_energy);
  GroupResult result;
  result.group = group;
  result.first_column = plan.GroupFirst(group);
  result.matrix_energy = *matrix_energy;
  size_t recomputed = 0, at = 0;  // start of the old column's slice
  CodedColumn coded;
  for (int j = 0; j < count; ++j) {
    if (Stopped(signals)) return absl::CancelledError(absl::StrCat("group ", group, ": cancelled"));
    const GroupColumn& was = old_result->columns[j];
    if (changed[j]) {
      ++recomputed;
      CodeColumn(params, images.subspan(j * image, image), &coded);
      AppendColumn(coded, &result);
    } else {
      GroupColumn kept = was;
      if (ctx.params.error_scope == ErrorScope::kMatrix) kept.reference_energy = *matrix_energy;
      result.columns.push_back(kept);
      result.positions.insert(result.positions.end(), old_result->positions.begin() + at,
                              old_result->positions.begin() + at + was.kept);
      result.values.insert(result.values.end(), old_result->values.begin() + at,
                           old_result->values.begin() + at + was.kept);
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
  return WriteCount(store, group, recomputed);
}

absl::StatusOr<int64_t> RecomputedColumns(const JobPlan& plan, const std::filesystem::path& store) {
  int64_t total = 0;
  for (int g = 0; g < plan.groups; ++g) {
    int64_t n = -1;
    {
      std::ifstream in(CountPath(store, g));
      if (!(in >> n) || n < 0) n = plan.GroupCount(g);
    }
    total += n;
    // Read once, by FINALIZE: a kept staging holds a full bake's files only.
    std::error_code ec;
    std::filesystem::remove(CountPath(store, g), ec);
  }
  return total;
}

}  // namespace wavebake
