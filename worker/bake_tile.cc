#include "worker/bake_tile.h"

#include <algorithm>
#include <system_error>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/columns/zero_quads.h"
#include "core/transport/refined_row.h"
#include "core/transport/transport_row.h"
#include "storage/store_layout.h"
#include "storage/zarr_array.h"
#include "worker/row_reuse.h"
#include "worker/row_transform.h"
#include "worker/staging.h"
#include "worker/task_buffer.h"

namespace wavebake {
namespace {

struct StagingArrays {
  ZarrArray transport;
  ZarrArray tile_energy;
};

absl::StatusOr<ZarrArray> OpenChecked(const std::filesystem::path& store, const char* name,
                                      const ArraySpec& expected) {
  absl::StatusOr<ZarrArray> array = ZarrArray::Open(store::Path(store, name));
  if (!array.ok()) return array.status();
  if (!SameSpec(array->spec(), expected)) {
    return absl::FailedPreconditionError(
        absl::StrCat(array->dir().string(), ": staging array ", ToZarray(array->spec()).dump(),
                     " does not match the job plan ", ToZarray(expected).dump()));
  }
  return array;
}

absl::StatusOr<StagingArrays> OpenStaging(const JobPlan& plan, const std::filesystem::path& store) {
  absl::StatusOr<ZarrArray> transport =
      OpenChecked(store, store::kStagingTransport, StagingTransportSpec(plan));
  if (!transport.ok()) return transport.status();
  absl::StatusOr<ZarrArray> energy =
      OpenChecked(store, store::kStagingTileEnergy, TileEnergySpec(plan));
  if (!energy.ok()) return energy.status();
  return StagingArrays{*std::move(transport), *std::move(energy)};
}

// Distance between consecutive rows in the tile's row buffer. M·4 bytes is a
// multiple of 4 KiB (M = 6N², N ≥ 8), so unpadded, the transpose's reads of
// one m across the rows would all fall into one L1 set; one extra cache line
// per row spreads them out (a stand-alone timing of the N=32, 32×32 tile
// transpose: 21–31 ms unpadded, 6–8 ms padded).
size_t RowStride(const JobPlan& plan) { return static_cast<size_t>(plan.columns) + 16; }

// Row-transformed rows of the cells of tile row `cy`, cell c of the tile at
// c*RowStride (masked cells all 0). Adds their Σ v² to `energy` while each
// row is still in cache; the fixed order (cell, then m) makes the sum the
// same bits on every worker.
void TraceTileRow(const BakeContext& ctx, const TileRect& rect, int cy, std::span<float> rows,
                  const std::vector<uint8_t>& reused, double& energy, TileStats& stats,
                  RefineScratch& scratch) {
  const int m_count = ctx.plan.columns;
  const int y = rect.y0 + cy;
  TransportStats traced;
  for (int cx = 0; cx < rect.width; ++cx) {
    const size_t cell = size_t(cy) * rect.width + cx;
    const std::span<float> row = rows.subspan(cell * RowStride(ctx.plan), m_count);
    const int32_t id = ctx.samples.grid[static_cast<size_t>(y) * ctx.samples.width + rect.x0 + cx];
    if (id < 0) {
      std::fill(row.begin(), row.end(), 0.0f);
      continue;
    }
    if (!reused.empty() && reused[cell]) {  // an update bake's old row: already staged values
      if (reused[cell] == 2) PatchRow(*ctx.reuse, ctx, id, row);
      energy += SumOfSquares(row.data(), row.size());
      ++stats.samples;
      continue;
    }
    if (ctx.params.transport == Transport::kVisibility) {
      VisibilityRow(ctx.caster, ctx.cubemap, ctx.jitter, ctx.samples.position[id],
                    ctx.samples.normal[id], ctx.epsilon, row, &traced);
    } else if (ctx.refine) {
      RefinedTransportRow(ctx.caster, ctx.cubemap, ctx.jitter, *ctx.refine,
                          ctx.samples.position[id], ctx.samples.normal[id], ctx.epsilon, row,
                          &traced, scratch);
    } else if (ctx.params.light_domain.is_plane()) {
      TransportRow(ctx.caster, ctx.jitter, ctx.samples.position[id], ctx.samples.normal[id],
                   ctx.epsilon, row, &traced);
    } else {  // the cube's faces in Z order
      TransportRow(ctx.caster, ctx.cubemap, ctx.jitter, ctx.samples.position[id],
                   ctx.samples.normal[id], ctx.epsilon, row, &traced);
    }
    RowTransform(ctx.params.row_filter, ctx.plan.light_res, row);
    energy += SumOfSquares(row.data(), row.size());
    ++stats.samples;
  }
  stats.rays_traced += traced.rays_traced;
}

// The blocked transpose (DESIGN.md §2) of one column group: chunk (g, tile)
// is [group_size, tile_cells] row major, column m of T over the tile
// contiguous; the rows past the last column (the last group's padding) are 0.
// Sixteen cells at a time, so that every write fills a whole cache line of
// the chunk (which stays in cache until it is compressed) and the sixteen
// rows read are reused for sixteen consecutive m.
void TransposeGroup(std::span<const float> rows, const JobPlan& plan, int g,
                    std::span<float> chunk) {
  const size_t cells = plan.tile_cells(), stride = RowStride(plan);
  const int first = plan.GroupFirst(g), count = plan.GroupCount(g);
  for (size_t c0 = 0; c0 < cells; c0 += 16) {
    const size_t width = std::min<size_t>(16, cells - c0);
    const float* in = rows.data() + c0 * stride + first;
    for (int j = 0; j < count; ++j) {
      float* out = chunk.data() + j * cells + c0;
      for (size_t i = 0; i < width; ++i) out[i] = in[i * stride + j];
    }
  }
  std::fill(chunk.begin() + size_t(count) * cells, chunk.end(), 0.0f);
}

absl::Status WriteChunkCounted(const ZarrArray& array, std::span<const int64_t> index,
                               std::span<const float> data, TileStats& stats) {
  if (absl::Status s = array.WriteChunk<float>(index, data); !s.ok()) return s;
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(array.ChunkPath(index), ec);
  if (!ec) stats.bytes_written += bytes;  // progress only: a failed stat fails no task
  return absl::OkStatus();
}

// Every group's chunk of the tile, each transposed just before it is
// compressed, then the tile's energy.
absl::Status WriteTile(const StagingArrays& staging, const JobPlan& plan, int tile,
                       std::span<const float> rows, double energy, TileStats& stats) {
  std::vector<float> chunk(static_cast<size_t>(plan.group_size) * plan.tile_cells());
  for (int g = 0; g < plan.groups; ++g) {
    TransposeGroup(rows, plan, g, chunk);
    const int64_t index[] = {g, tile};
    if (absl::Status s = WriteChunkCounted(staging.transport, index, chunk, stats); !s.ok())
      return s;
  }
  const float tile_energy[] = {static_cast<float>(energy)};
  const int64_t index[] = {tile};
  return WriteChunkCounted(staging.tile_energy, index, tile_energy, stats);
}

}  // namespace

absl::Status BakeTile(const BakeContext& ctx, const std::filesystem::path& store, int tile,
                      TileStats* stats, const TaskSignals& signals) {
  const JobPlan& plan = ctx.plan;
  if (tile < 0 || tile >= plan.tiles()) {
    return absl::InvalidArgumentError(
        absl::StrCat("tile: ", tile, " is outside 0..", plan.tiles() - 1));
  }
  absl::StatusOr<StagingArrays> staging = OpenStaging(plan, store);
  if (!staging.ok()) return staging.status();

  const TileRect rect = plan.Tile(tile);
  const std::span<float> rows = TaskBuffer(plan.tile_cells() * RowStride(plan));
  TileStats local;
  double energy = 0;
  RefineScratch scratch;
  std::vector<uint8_t> reused;  // per cell of the tile: its row came from an old store
  if (ctx.reuse) {
    absl::StatusOr<int> n = FillReusedRows(*ctx.reuse, plan, tile, rows, RowStride(plan), reused);
    if (!n.ok()) return n.status();
    local.rows_reused = static_cast<uint64_t>(*n);
  }
  for (int cy = 0; cy < rect.height; ++cy) {
    if (signals.cancel && signals.cancel->load(std::memory_order_relaxed))
      return absl::CancelledError(absl::StrCat("tile: ", tile, " cancelled"));
    TraceTileRow(ctx, rect, cy, rows, reused, energy, local, scratch);
    if (signals.rays_traced)
      signals.rays_traced->store(local.rays_traced, std::memory_order_relaxed);
  }
  absl::Status written = WriteTile(*staging, plan, tile, rows, energy, local);
  if (stats) {
    stats->rays_traced += local.rays_traced;
    stats->bytes_written += local.bytes_written;
    stats->samples += local.samples;
    stats->rows_reused += local.rows_reused;
  }
  return written;
}

}  // namespace wavebake
