#include "worker/tiles/bake_tile.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <optional>
#include <system_error>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/columns/zero_quads.h"
#include "core/transport/refined_row.h"
#include "core/transport/transport_row.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"
#include "worker/loop/task_buffer.h"
#include "worker/tiles/changed_columns.h"
#include "worker/tiles/row_reuse.h"
#include "worker/tiles/row_transform.h"
#include "worker/tiles/staging.h"

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

// One sample's direct row, traced as the parameters say.
void TraceRow(const BakeContext& ctx, Vec3 position, Vec3 normal, std::span<float> row,
              TransportStats* traced, RefineScratch& scratch) {
  if (ctx.params.transport == Transport::kVisibility) {
    VisibilityRow(ctx.caster, ctx.cubemap, ctx.jitter, position, normal, ctx.epsilon, row, traced);
  } else if (ctx.refine) {
    RefinedTransportRow(ctx.caster, ctx.cubemap, ctx.jitter, *ctx.refine, position, normal,
                        ctx.epsilon, row, traced, scratch);
  } else if (ctx.params.light_domain.is_plane()) {
    TransportRow(ctx.caster, ctx.jitter, position, normal, ctx.epsilon, row, traced);
  } else {  // the cube's faces in Z order
    TransportRow(ctx.caster, ctx.cubemap, ctx.jitter, position, normal, ctx.epsilon, row, traced);
  }
}

// Row-transformed rows of the cells of tile row `cy`, cell x of the row at
// x*RowStride of `rows` (masked cells all 0); `reused` (empty, or one per
// cell of the row) marks an update's old rows. Adds their Σ v² to `energy`
// while each row is still in cache; the fixed order (cell, then m) makes the
// sum the same bits on every worker. A patched row marks in `changed` (if
// given) the columns its patch changes.
void TraceTileRow(const BakeContext& ctx, const TileRect& rect, int cy, std::span<float> rows,
                  std::span<const uint8_t> reused, double& energy, TileStats& stats,
                  RefineScratch& scratch, std::span<uint8_t> changed) {
  const int m_count = ctx.plan.columns;
  const int y = rect.y0 + cy;
  TransportStats traced;
  for (int cx = 0; cx < rect.width; ++cx) {
    const std::span<float> row = rows.subspan(size_t(cx) * RowStride(ctx.plan), m_count);
    const int32_t id = ctx.samples.grid[static_cast<size_t>(y) * ctx.samples.width + rect.x0 + cx];
    if (id < 0) {
      std::fill(row.begin(), row.end(), 0.0f);
      continue;
    }
    if (!reused.empty() && reused[cx]) {  // an update bake's old row: already staged values
      if (reused[cx] == 2) PatchRow(*ctx.reuse, ctx, id, row, changed);
      energy += SumOfSquares(row.data(), row.size());
      ++stats.samples;
      continue;
    }
    TraceRow(ctx, ctx.samples.position[id], ctx.samples.normal[id], row, &traced, scratch);
    RowTransform(ctx.params.row_filter, ctx.plan.light_res, row);
    energy += SumOfSquares(row.data(), row.size());
    ++stats.samples;
  }
  stats.rays_traced += traced.rays_traced;
}

// How a transposed chunk is written: the store path compresses it at once,
// so its lines should stay in cache; memory staging reads it only in
// TRANSFORM_COLUMNS, a phase later, so there its whole lines are streamed
// past the caches (non-temporal stores need no read for ownership and evict
// none of the rows being read; docs/RESULTS.md has the timings).
enum class ChunkWrites { kCached, kStreamed };

// out[0..15] = in[0], in[stride], …, in[15·stride], one 64-byte line of the
// chunk (`out` 64-byte aligned), written past the caches where the target
// has streaming stores.
void StreamLine(float* out, const float* in, size_t stride) {
#if defined(__SSE2__)
  for (size_t i = 0; i < 16; i += 4) {
    const float* r = in + i * stride;
    _mm_stream_ps(out + i, _mm_set_ps(r[3 * stride], r[2 * stride], r[stride], r[0]));
  }
#else
  for (size_t i = 0; i < 16; ++i) out[i] = in[i * stride];
#endif
}

// The blocked transpose (DESIGN.md §2) of one column group: chunk (g, tile)
// is [group_size, tile_cells] row major, column m of T over the tile
// contiguous; the rows past the last column (the last group's padding) are 0.
// `rows` holds the rows of cells [first_cell, first_cell + n) of the tile,
// and only those cells of the chunk are written. Sixteen cells at a time,
// so that every write fills a whole cache line of the chunk and the sixteen
// rows read are reused for sixteen consecutive m.
void TransposeGroup(std::span<const float> rows, const JobPlan& plan, int g, std::span<float> chunk,
                    size_t first_cell, size_t n, ChunkWrites writes = ChunkWrites::kCached) {
  const size_t cells = plan.tile_cells(), stride = RowStride(plan);
  const int first = plan.GroupFirst(g), count = plan.GroupCount(g);
  const bool stream = writes == ChunkWrites::kStreamed;
  for (size_t c0 = 0; c0 < n; c0 += 16) {
    const size_t width = std::min<size_t>(16, n - c0);
    const float* in = rows.data() + c0 * stride + first;
    for (int j = 0; j < count; ++j) {
      float* out = chunk.data() + j * cells + first_cell + c0;
      if (stream && width == 16 && reinterpret_cast<uintptr_t>(out) % 64 == 0) {
        StreamLine(out, in + j, stride);
        continue;
      }
      for (size_t i = 0; i < width; ++i) out[i] = in[i * stride + j];
    }
  }
  for (int j = count; j < plan.group_size; ++j)
    std::fill_n(chunk.begin() + j * cells + first_cell, n, 0.0f);
#if defined(__SSE2__)
  if (stream) _mm_sfence();  // the streamed lines are visible before the chunk is published
#endif
}

// Rows traced at a time into an in-memory staging: a band of cells whose
// rows stay in the last-level cache while they are transposed, rather than a
// whole tile's (100 MB per worker thread at N = 64, 400 MB at 128), whose
// first touch alone cost 6 % of a refined bake's CPU on these machines.
constexpr size_t kBandBytes = size_t{4} << 20;
size_t BandCells(const JobPlan& plan) {
  const size_t fit = kBandBytes / (RowStride(plan) * sizeof(float));
  return std::clamp<size_t>(fit / 16 * 16, 16, plan.tile_cells());
}

// One tile's chunks of an in-memory staging, begun together, written band
// by band and published together; an attempt that stops early (an error, a
// cancel) abandons them for the next. A chunk another attempt holds is
// skipped (the same values: they depend only on the context and the tile).
class TileSlots {
 public:
  TileSlots(MemoryStaging::Job& job, const JobPlan& plan, int slot_tile)
      : job_(job), plan_(plan), tile_(slot_tile), slots_(plan.groups) {
    for (int g = 0; g < plan.groups; ++g) slots_[g] = job.BeginWrite(g, slot_tile);
  }
  ~TileSlots() {
    for (int g = 0; g < plan_.groups; ++g)
      if (!published_ && !slots_[g].empty()) job_.Abandon(g, tile_);
  }
  TileSlots(const TileSlots&) = delete;
  TileSlots& operator=(const TileSlots&) = delete;

  void Write(std::span<const float> rows, size_t first_cell, size_t cells) {
    for (int g = 0; g < plan_.groups; ++g)
      if (!slots_[g].empty())
        TransposeGroup(rows, plan_, g, slots_[g], first_cell, cells, ChunkWrites::kStreamed);
  }
  void Publish() {
    for (int g = 0; g < plan_.groups; ++g)
      if (!slots_[g].empty()) job_.Publish(g, tile_);
    published_ = true;
  }

 private:
  MemoryStaging::Job& job_;
  const JobPlan& plan_;
  int tile_;
  std::vector<std::span<float>> slots_;  // per group; empty: another attempt's
  bool published_ = false;
};

absl::Status WriteChunkCounted(const ZarrArray& array, std::span<const int64_t> index,
                               std::span<const float> data, TileStats& stats) {
  if (absl::Status s = array.WriteChunk<float>(index, data); !s.ok()) return s;
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(array.ChunkPath(index), ec);
  if (!ec) stats.bytes_written += bytes;  // progress only: a failed stat fails no task
  return absl::OkStatus();
}

// Chunk `index` of `from`, copied into `to` as it was encoded (the same spec).
absl::Status CopyChunkCounted(const ZarrArray& to, const ZarrArray& from,
                              std::span<const int64_t> index, TileStats& stats) {
  if (absl::Status s = to.CopyChunkFrom(from, index); !s.ok()) return s;
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(to.ChunkPath(index), ec);
  if (!ec) stats.bytes_written += bytes;
  return absl::OkStatus();
}

// Where an in-place update's tile finds the chunks it did not change: the
// old staging, whose chunk (g, tile) holds the same cells.
struct UnchangedChunks {
  const ZarrArray* old = nullptr;
  std::span<const uint8_t> changed;  // per column of the plan (worker/tiles/changed_columns.h)

  bool Holds(const JobPlan& plan, int g) const {
    if (old == nullptr) return false;
    const auto columns = changed.subspan(plan.GroupFirst(g), plan.GroupCount(g));
    return std::find(columns.begin(), columns.end(), 1) == columns.end();
  }
};

// Every group's chunk of the tile into `transport`, each transposed just
// before it is compressed, or, where `unchanged` holds it, copied as it was
// encoded (the same values: the same bits).
absl::Status WriteTileChunks(const ZarrArray& transport, const JobPlan& plan, int tile,
                             std::span<const float> rows, TileStats& stats,
                             const UnchangedChunks& unchanged = {}) {
  std::vector<float> chunk(static_cast<size_t>(plan.group_size) * plan.tile_cells());
  for (int g = 0; g < plan.groups; ++g) {
    const int64_t index[] = {g, tile};
    if (unchanged.Holds(plan, g)) {
      absl::Status s = CopyChunkCounted(transport, *unchanged.old, index, stats);
      if (s.ok()) continue;
      if (!absl::IsNotFound(s)) return s;  // not staged there: written anew
    }
    TransposeGroup(rows, plan, g, chunk, 0, plan.tile_cells());
    if (absl::Status s = WriteChunkCounted(transport, index, chunk, stats); !s.ok()) return s;
  }
  return absl::OkStatus();
}

absl::Status WriteTileEnergy(const StagingArrays& staging, int tile, double energy,
                             TileStats& stats) {
  const float tile_energy[] = {static_cast<float>(energy)};
  const int64_t index[] = {tile};
  return WriteChunkCounted(staging.tile_energy, index, tile_energy, stats);
}

bool HasSamples(const BakeContext& ctx, const TileRect& r) {
  for (int y = r.y0; y < r.y0 + r.height; ++y)
    for (int x = r.x0; x < r.x0 + r.width; ++x)
      if (ctx.samples.grid[size_t(y) * ctx.samples.width + x] >= 0) return true;
  return false;
}

// Auxiliary tile `a` (core/bake/bake_gather.h): the direct rows of auxiliary
// samples a·tile_cells.., into staging/aux_transport; the padding past the
// last one and the rows no bounce reads (BakeGathers::aux_rows) are 0. Not
// part of the matrix, so no tile energy.
absl::Status BakeAuxTile(const BakeContext& ctx, const std::filesystem::path& store, int a,
                         TileStats& local, const TaskSignals& signals, MemoryStaging::Job* memory) {
  const JobPlan& plan = ctx.plan;
  if (!ctx.bounce || ctx.bounce->aux.size() != plan.aux_samples)
    return absl::FailedPreconditionError("bounces: the context has no auxiliary samples");
  absl::StatusOr<ZarrArray> transport =
      OpenChecked(store, store::kStagingAuxTransport, AuxTransportSpec(plan));
  if (!transport.ok()) return transport.status();
  const SampleSet& aux = ctx.bounce->aux;
  // In memory, a band of cells at a time (BandCells); else the whole tile,
  // whose chunks are compressed whole.
  const size_t cells = plan.tile_cells(), band = memory ? BandCells(plan) : cells;
  const std::span<float> rows = TaskBuffer(band * RowStride(plan));
  std::optional<TileSlots> slots;
  if (memory) slots.emplace(*memory, plan, plan.tiles() + a);
  RefineScratch scratch;
  TransportStats traced;
  for (size_t cell = 0; cell < cells; ++cell) {
    if (cell % 64 == 0 && signals.cancel && signals.cancel->load(std::memory_order_relaxed))
      return absl::CancelledError(absl::StrCat("tile: ", plan.tiles() + a, " cancelled"));
    const std::span<float> row = rows.subspan(cell % band * RowStride(plan), plan.columns);
    const size_t id = a * cells + cell;
    if (id >= static_cast<size_t>(aux.size()) || !ctx.bounce->aux_rows[id]) {
      std::fill(row.begin(), row.end(), 0.0f);
    } else {
      TraceRow(ctx, aux.position[id], aux.normal[id], row, &traced, scratch);
      RowTransform(ctx.params.row_filter, plan.light_res, row);
      ++local.samples;
      if (signals.rays_traced)
        signals.rays_traced->store(traced.rays_traced, std::memory_order_relaxed);
    }
    if (slots && (cell % band == band - 1 || cell == cells - 1))
      slots->Write(rows, cell / band * band, cell % band + 1);
  }
  local.rays_traced += traced.rays_traced;
  if (!slots) return WriteTileChunks(*transport, plan, a, rows, local);
  slots->Publish();
  return absl::OkStatus();
}

// An update's tile whose every row is an old row in its old cell (none
// traced, patched or masked otherwise: RowReuse::tile_touched) stages what
// the old store staged, bit for bit (the energy too: the same rows summed in
// the same order), so its chunks are copied as encoded instead of decoded,
// transposed back, transposed again and encoded. False if it is not such a
// tile or the old store lacks one of its chunks (then it is baked).
absl::StatusOr<bool> CopyUnchangedTile(const BakeContext& ctx, const StagingArrays& staging,
                                       int tile, TileStats& stats) {
  const RowReuse& reuse = *ctx.reuse;
  if (!reuse.in_place || reuse.tile_touched.empty() || reuse.tile_touched[tile]) return false;
  absl::StatusOr<StagingArrays> old = OpenStaging(ctx.plan, reuse.old_store);
  if (!old.ok()) return old.status();
  for (int g = 0; g < ctx.plan.groups; ++g) {
    const int64_t index[] = {g, tile};
    absl::Status s = CopyChunkCounted(staging.transport, old->transport, index, stats);
    if (absl::IsNotFound(s)) return false;
    if (!s.ok()) return s;
  }
  const int64_t index[] = {tile};
  absl::Status s = CopyChunkCounted(staging.tile_energy, old->tile_energy, index, stats);
  if (absl::IsNotFound(s)) return false;
  if (!s.ok()) return s;
  const TileRect rect = ctx.plan.Tile(tile);
  for (int y = rect.y0; y < rect.y0 + rect.height; ++y)
    for (int x = rect.x0; x < rect.x0 + rect.width; ++x)
      stats.samples += ctx.samples.grid[size_t(y) * ctx.samples.width + x] >= 0;
  stats.rows_reused = stats.samples;
  return true;
}

// The tile's chunks into the store's staging. An update that records its
// changed columns (`rewritten`: the old rows of the cells the tile
// rewrites) writes them first, and copies as encoded the old staging's
// chunks of groups it did not change.
absl::Status WriteChunksToStore(const BakeContext& ctx, const std::filesystem::path& store,
                                const ZarrArray& transport, int tile, std::span<const float> rows,
                                const OldRows* rewritten, std::span<uint8_t> changed,
                                TileStats& stats) {
  if (rewritten == nullptr) return WriteTileChunks(transport, ctx.plan, tile, rows, stats);
  OrChangedColumns(*rewritten, rows, RowStride(ctx.plan), changed);
  if (absl::Status s = WriteChangedColumns(store, tile, changed); !s.ok()) return s;
  absl::StatusOr<StagingArrays> old = OpenStaging(ctx.plan, ctx.reuse->old_store);
  if (!old.ok()) return old.status();
  return WriteTileChunks(transport, ctx.plan, tile, rows, stats,
                         {.old = &old->transport, .changed = changed});
}

}  // namespace

absl::Status BakeTile(const BakeContext& ctx, const std::filesystem::path& store, int tile,
                      TileStats* stats, const TaskSignals& signals, MemoryStaging* memory) {
  const JobPlan& plan = ctx.plan;
  if (tile < 0 || tile >= plan.all_tiles()) {
    return absl::InvalidArgumentError(
        absl::StrCat("tile: ", tile, " is outside 0..", plan.all_tiles() - 1));
  }
  const bool in_memory = memory != nullptr && !ctx.params.keep_staging && !ctx.reuse;
  if (tile >= plan.tiles()) {
    TileStats local;
    const std::shared_ptr<MemoryStaging::Job> held =
        in_memory ? memory->Admit(store, plan) : nullptr;
    absl::Status s = BakeAuxTile(ctx, store, tile - plan.tiles(), local, signals, held.get());
    if (stats) {
      stats->rays_traced += local.rays_traced;
      stats->bytes_written += local.bytes_written;
      stats->samples += local.samples;
    }
    return s;
  }
  absl::StatusOr<StagingArrays> staging = OpenStaging(plan, store);
  if (!staging.ok()) return staging.status();

  const TileRect rect = plan.Tile(tile);
  const std::shared_ptr<MemoryStaging::Job> held = in_memory ? memory->Admit(store, plan) : nullptr;
  TileStats local;
  if (held != nullptr && !HasSamples(ctx, rect)) {
    // Every chunk of a tile without samples is zeros: in memory, pages never
    // written read as zeros, and none is touched (the bunny at hilbert 64²
    // covers 3 of its 4 tiles).
    for (int g = 0; g < plan.groups; ++g)
      if (!held->BeginWrite(g, tile).empty()) held->Publish(g, tile);
    const absl::Status written = WriteTileEnergy(*staging, tile, 0.0, local);
    if (stats) stats->bytes_written += local.bytes_written;
    return written;
  }
  if (ctx.reuse) {
    absl::StatusOr<bool> copied = CopyUnchangedTile(ctx, *staging, tile, local);
    if (!copied.ok()) return copied.status();
    if (*copied) {
      if (stats) {
        stats->bytes_written += local.bytes_written;
        stats->samples += local.samples;
        stats->rows_reused += local.rows_reused;
      }
      return absl::OkStatus();
    }
  }
  // In memory, bands of whole tile rows (BandCells); else the whole tile,
  // whose chunks are compressed whole.
  const size_t stride = RowStride(plan), tile_width = size_t(rect.width);
  const int band_rows =
      held ? static_cast<int>(std::max<size_t>(1, BandCells(plan) / tile_width)) : rect.height;
  const std::span<float> rows = TaskBuffer(size_t(band_rows) * tile_width * stride);
  std::optional<TileSlots> slots;
  if (held) slots.emplace(*held, plan, tile);
  double energy = 0;
  RefineScratch scratch;
  std::vector<uint8_t> reused;  // per cell of the tile: its row came from an old store
  // An in-place --update that codes only changed columns records those the
  // tile changes (worker/tiles/changed_columns.h) from the old rows of the
  // cells it rewrites.
  const bool records_changes = CodesChangedColumnsOnly(ctx) && ctx.reuse->in_place;
  // Per thread, reused tile after tile: a fresh buffer would be zero-filled
  // and first-touched for every tile, only to be overwritten.
  thread_local OldRows rewritten;
  std::vector<uint8_t> changed(records_changes ? plan.columns : 0, 0);
  if (ctx.reuse) {
    absl::StatusOr<int> n = FillReusedRows(*ctx.reuse, plan, tile, rows, RowStride(plan), reused,
                                           records_changes ? &rewritten : nullptr);
    if (!n.ok()) return n.status();
    local.rows_reused = static_cast<uint64_t>(*n);
  }
  for (int cy = 0; cy < rect.height; ++cy) {
    if (signals.cancel && signals.cancel->load(std::memory_order_relaxed))
      return absl::CancelledError(absl::StrCat("tile: ", tile, " cancelled"));
    const int in_band = cy % band_rows;
    const std::span<const uint8_t> reused_row =
        reused.empty() ? std::span<const uint8_t>()
                       : std::span<const uint8_t>(reused).subspan(cy * tile_width, tile_width);
    TraceTileRow(ctx, rect, cy, rows.subspan(in_band * tile_width * stride), reused_row, energy,
                 local, scratch, changed);
    if (signals.rays_traced)
      signals.rays_traced->store(local.rays_traced, std::memory_order_relaxed);
    if (slots && (in_band == band_rows - 1 || cy == rect.height - 1))
      slots->Write(rows, (cy - in_band) * tile_width, (in_band + 1) * tile_width);
  }
  absl::Status written = absl::OkStatus();
  if (slots) {
    slots->Publish();
  } else {
    written = WriteChunksToStore(ctx, store, staging->transport, tile, rows,
                                 records_changes ? &rewritten : nullptr, changed, local);
  }
  if (written.ok()) written = WriteTileEnergy(*staging, tile, energy, local);
  if (stats) {
    stats->rays_traced += local.rays_traced;
    stats->bytes_written += local.bytes_written;
    stats->samples += local.samples;
    stats->rows_reused += local.rows_reused;
  }
  return written;
}

}  // namespace wavebake
