#include "worker/columns/transform_columns.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/columns/column_coding.h"
#include "core/columns/group_codings.h"
#include "core/columns/zero_quads.h"
#include "storage/store/store_layout.h"
#include "storage/store/transport_bytes.h"
#include "storage/zarr/zarr_array.h"
#include "worker/columns/column_bounces.h"
#include "worker/columns/group_result.h"
#include "worker/columns/shard_plan.h"
#include "worker/loop/task_buffer.h"

namespace wavebake {
namespace {

absl::Status WrongPlan(const ZarrArray& a, const std::string& what) {
  return absl::FailedPreconditionError(
      absl::StrCat(a.dir().string(), ": ", what, " does not match the job plan"));
}

// Opens staging/transport and checks it is the layout of this plan
// (core/bake/job_plan.h): [M, W*H] float32 chunked [group_size, tile_cells].
absl::StatusOr<ZarrArray> OpenStaging(const JobPlan& plan, const std::filesystem::path& store) {
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(store::Path(store, store::kStagingTransport));
  if (absl::IsNotFound(a.status()))
    return absl::FailedPreconditionError(absl::StrCat(a.status().message(), " (no staging)"));
  if (!a.ok()) return a.status();
  const ArraySpec& s = a->spec();
  if (s.dtype != DType::kFloat32) return WrongPlan(*a, "dtype");
  if (s.shape != std::vector<int64_t>{plan.columns, int64_t{plan.width} * plan.height})
    return WrongPlan(*a, "shape");
  if (s.chunks != std::vector<int64_t>{plan.group_size, plan.tile_cells()})
    return WrongPlan(*a, "chunking");
  return a;
}

bool Stopped(const TaskSignals& signals) {
  return signals.cancel != nullptr && signals.cancel->load(std::memory_order_relaxed);
}

absl::Status Cancelled(int group) {
  return absl::CancelledError(absl::StrCat("group ", group, ": cancelled"));
}

}  // namespace

// The tiles cover the image, so every element is written. A chunk the job's
// in-memory staging does not hold must be in the store (a tile whose energy
// is written has written its chunks somewhere).
absl::Status AssembleColumns(const JobPlan& plan, const ZarrArray& staging,
                             const MemoryStaging::Job* memory, int group, std::span<float> images,
                             GroupStats* stats, const TaskSignals& signals,
                             std::span<const int> columns) {
  const int count = columns.empty() ? plan.GroupCount(group) : static_cast<int>(columns.size());
  const size_t cells = size_t(plan.width) * plan.height;
  std::vector<float> buffer;
  for (int t = 0; t < plan.tiles(); ++t) {
    if (Stopped(signals)) return Cancelled(group);
    std::span<const float> chunk = memory ? memory->Chunk(group, t) : std::span<const float>();
    if (chunk.empty()) {
      const int64_t index[2] = {group, t};
      if (memory != nullptr && !std::filesystem::exists(staging.ChunkPath(index)))
        return absl::FailedPreconditionError(absl::StrCat(
            staging.dir().string(), ": chunk ", group, ".", t, " is neither in memory nor staged"));
      buffer.resize(size_t(plan.group_size) * plan.tile_cells());
      if (absl::Status s = staging.ReadChunkInto(index, std::as_writable_bytes(std::span(buffer)));
          !s.ok()) {
        return s;
      }
      chunk = buffer;
    }
    stats->staging_bytes += chunk.size() * sizeof(float);
    const TileRect r = plan.Tile(t);
    for (int k = 0; k < count; ++k) {
      const int c = columns.empty() ? k : columns[k];
      const float* src = chunk.data() + size_t(c) * plan.tile_cells();
      float* dst = images.data() + k * cells + size_t(r.y0) * plan.width + r.x0;
      for (int y = 0; y < r.height; ++y) {
        std::copy_n(src + size_t(y) * r.width, r.width, dst + size_t(y) * plan.width);
      }
    }
  }
  return absl::OkStatus();
}

bool KeepsItsDepth(const ColumnCodingParams& p, const GroupColumn& was,
                   std::span<const float> column) {
  constexpr double kDepthKeptChange = 0.25;
  if (p.mode != ColumnMode::kAdaptive || was.kept == 0) return false;
  const double energy = SumOfSquares(column.data(), column.size());
  return std::abs(energy - was.energy) <= kDepthKeptChange * was.energy;
}

// The group's result for FINALIZE: held in the job's in-memory staging
// where it fits (memory, if not null), else written to staging/groups.
// Returns the bytes written to the store (0 if held).
absl::StatusOr<uint64_t> PutGroupResult(const std::filesystem::path& store, MemoryStaging* memory,
                                        std::shared_ptr<const GroupResult> result) {
  // A FINALIZE plan worked out from the group results before is not this one's.
  if (absl::Status s = RemoveShardPlan(store); !s.ok()) return s;
  const uint64_t held_bytes = result->positions.size() * sizeof(uint32_t) +
                              result->values.size() * sizeof(float) +
                              result->columns.size() * sizeof(GroupColumn);
  if (memory != nullptr && memory->HoldGroup(store, result->group, result, held_bytes)) return 0;
  if (absl::Status s = WriteGroupResult(store, *result); !s.ok()) return s;
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(GroupResultPath(store, result->group), ec);
  return ec ? 0 : bytes;  // progress only: a failed stat fails no task
}

absl::StatusOr<double> ReadMatrixEnergy(const JobPlan& plan, const std::filesystem::path& store) {
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(store::Path(store, store::kStagingTileEnergy));
  if (!a.ok()) return a.status();
  if (a->spec().shape != std::vector<int64_t>{plan.tiles()} || a->spec().chunks.at(0) != 1)
    return WrongPlan(*a, "shape");
  double sum = 0;
  for (int64_t t = 0; t < plan.tiles(); ++t) {
    // A missing chunk would read as 0: a tile not baked yet, not an empty one.
    if (!std::filesystem::exists(a->ChunkPath(std::span(&t, 1))))
      return absl::FailedPreconditionError(
          absl::StrCat(a->dir().string(), ": tile ", t, " has not been baked"));
    absl::StatusOr<std::vector<float>> e = a->ReadChunk<float>(std::span(&t, 1));
    if (!e.ok()) return e.status();
    sum += (*e)[0];
  }
  return sum / plan.columns;
}

std::optional<CellFiller> UncoveredFiller(const BakeContext& ctx) {
  if (ctx.layout.kind != LayoutKind::kUv || ctx.layout.fill == UncoveredFill::kZero)
    return std::nullopt;
  return std::optional<CellFiller>(std::in_place, ctx.layout.fill, ctx.samples.grid, ctx.plan.width,
                                   ctx.plan.height);
}

absl::Status TransformColumns(const BakeContext& ctx, const std::filesystem::path& store, int group,
                              GroupStats* stats, const TaskSignals& signals, MemoryStaging* memory,
                              const GroupResult* old) {
  const JobPlan& plan = ctx.plan;
  if (group < 0 || group >= plan.groups)
    return absl::InvalidArgumentError(
        absl::StrCat("group: ", group, " is outside 0..", plan.groups - 1));
  absl::StatusOr<ZarrArray> staging = OpenStaging(plan, store);
  if (!staging.ok()) return staging.status();
  absl::StatusOr<double> matrix_energy = ReadMatrixEnergy(plan, store);
  if (!matrix_energy.ok()) return matrix_energy.status();

  if (old != nullptr && old->columns.size() != size_t(plan.GroupCount(group))) old = nullptr;
  GroupStats local;
  const std::span<float> images =
      TaskBuffer(size_t(plan.GroupCount(group)) * plan.width * plan.height);
  const std::shared_ptr<MemoryStaging::Job> held = memory ? memory->Find(store) : nullptr;
  if (absl::Status s = AssembleColumns(plan, *staging, held.get(), group, images, &local, signals);
      !s.ok())
    return s;
  ColumnCodingParams params =
      MakeColumnCodingParams(ctx.params, plan.width, plan.height, *matrix_energy);
  // Diffuse interreflection, added to the column images before they are coded.
  std::vector<double> left_out(plan.GroupCount(group), 0.0);
  const bool budgeted = params.column_terms == 0 && params.scope == ErrorScope::kMatrix;
  const BounceTruncation truncation{
      .threshold =
          budgeted ? kBounceShare * params.target_error * params.target_error * params.matrix_energy
                   : 0.0,
      .left_out = left_out};
  if (absl::Status s = AddGroupBounces(ctx, store, group, images, truncation, signals, held.get());
      !s.ok())
    return s;

  const std::optional<CellFiller> filler = UncoveredFiller(ctx);
  if (filler) params.filler = &*filler;
  const size_t cells = size_t(plan.width) * plan.height;
  GroupResult result;
  result.group = group;
  result.first_column = plan.GroupFirst(group);
  result.matrix_energy = *matrix_energy;
  // Each column's fewest-coefficient coding and, for adaptive by size, its
  // depth-0 one; the group keeps the choice its arrays code smallest in
  // (core/columns/group_codings.h).
  std::vector<ColumnCodings> codings(plan.GroupCount(group));
  for (int c = 0; c < plan.GroupCount(group); ++c) {
    if (Stopped(signals)) return Cancelled(group);
    const std::span<const float> image = images.subspan(c * cells, cells);
    if (old != nullptr && KeepsItsDepth(params, old->columns[c], image)) {
      // No depth-0 alternative either: the old depth already is the group's choice.
      CodeColumnAtDepth(params, image, old->columns[c].depth, &codings[c].fewest, left_out[c]);
      codings[c].flat = NoCoding();
    } else {
      ++local.searched;
      CodeColumn(params, image, &codings[c].fewest, left_out[c], &codings[c].flat);
    }
  }
  const std::vector<uint8_t> use_flat =
      ChooseGroupCodings(params, codings, plan.GroupFirst(group), TransportBytes);
  for (size_t c = 0; c < codings.size(); ++c) {
    const CodedColumn& coded = use_flat[c] ? codings[c].flat : codings[c].fewest;
    AppendColumn(coded, &result);
    local.min_bits = std::max(local.min_bits, coded.min_bits);
  }
  local.columns = plan.GroupCount(group);
  local.kept = result.positions.size();
  const absl::StatusOr<uint64_t> bytes =
      PutGroupResult(store, memory, std::make_shared<const GroupResult>(std::move(result)));
  if (!bytes.ok()) return bytes.status();
  local.bytes_written = *bytes;
  if (stats != nullptr) *stats = local;
  return absl::OkStatus();
}

}  // namespace wavebake
