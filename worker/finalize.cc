#include "worker/finalize.h"

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/columns/column_coding.h"
#include "core/columns/quantization_steps.h"
#include "core/columns/quantizer.h"
#include "core/wavelets/subband.h"
#include "core/wavelets/wavelet2d.h"
#include "storage/array_appender.h"
#include "storage/atomic_file.h"
#include "storage/store_layout.h"
#include "storage/store_samples.h"
#include "storage/zarr_array.h"
#include "worker/bounce_record.h"
#include "worker/group_result.h"
#include "worker/ordered_parallel.h"
#include "worker/store_manifest.h"
#include "worker/store_stats.h"

namespace wavebake {
namespace {

// Chunk lengths of the final arrays: ~1 MB of indices, 512 KB of data.
constexpr int64_t kNnzChunk = 1 << 18;
constexpr int64_t kColumnChunk = 1 << 16;

absl::Status CheckGroup(const JobPlan& plan, const std::filesystem::path& store, int g,
                        const GroupResult& r) {
  if (r.first_column == plan.GroupFirst(g) &&
      r.columns.size() == static_cast<size_t>(plan.GroupCount(g))) {
    return absl::OkStatus();
  }
  return absl::DataLossError(
      absl::StrCat(GroupResultPath(store, g).string(), ": columns do not match the job plan"));
}

// Pass 1: nnz (the length of indices/data) and what the step choice needs to
// know of every column (O(M)), from the groups' column tables alone. A
// missing group is FailedPrecondition: FINALIZE ran too early.
struct GroupScan {
  int64_t nnz = 0;
  std::vector<ColumnQuantInput> columns;
};

absl::Status Stopped(const FinalizeOptions& options, int group) {
  if (options.cancel == nullptr || !options.cancel->load()) return absl::OkStatus();
  return absl::CancelledError(absl::StrCat("FINALIZE: cancelled at group ", group));
}

// Threads of FINALIZE's own: it runs alone at the end of a job.
int Threads(const FinalizeOptions& options) {
  return options.threads > 0 ? options.threads
                             : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Group g's result (only its column table if `columns_only`), checked
// against the plan; FailedPrecondition if it is missing (FINALIZE ran too
// early).
absl::StatusOr<GroupResult> ReadCheckedGroup(const JobPlan& plan,
                                             const std::filesystem::path& store,
                                             const FinalizeOptions& options, int g,
                                             bool columns_only = false) {
  if (absl::Status s = Stopped(options, g); !s.ok()) return s;
  absl::StatusOr<GroupResult> r =
      columns_only ? ReadGroupColumns(store, g) : ReadGroupResult(store, g);
  if (absl::IsNotFound(r.status()))
    return absl::FailedPreconditionError(
        absl::StrCat("group ", g, " has not been transformed: ", r.status().message()));
  if (!r.ok()) return r.status();
  if (absl::Status s = CheckGroup(plan, store, g, *r); !s.ok()) return s;
  return r;
}

absl::Status ScanGroups(const JobPlan& plan, const std::filesystem::path& store,
                        const FinalizeOptions& options, GroupScan* scan) {
  *scan = {};
  struct Columns {
    int64_t kept = 0;
    std::vector<ColumnQuantInput> columns;
  };
  const int threads = Threads(options);
  return OrderedParallel<Columns>(
      plan.groups, threads, 2 * threads,
      [&](int g) -> absl::StatusOr<Columns> {
        absl::StatusOr<GroupResult> r = ReadCheckedGroup(plan, store, options, g, true);
        if (!r.ok()) return r.status();
        Columns out;
        for (const GroupColumn& c : r->columns) {
          out.kept += c.kept;
          out.columns.push_back({.max_abs = c.max_abs,
                                 .step_unit = c.step_unit,
                                 .reference_energy = c.reference_energy,
                                 .min_bits = c.min_bits});
        }
        return out;
      },
      [&](int, Columns& c) {
        scan->nnz += c.kept;
        scan->columns.insert(scan->columns.end(), c.columns.begin(), c.columns.end());
        return absl::OkStatus();
      });
}

struct CscArrays {
  ZarrArray indptr, indices, data, depth, scale;
};

// zstd levels of the nnz-long arrays (zstd 1.5.4, measured on the N=64
// stores of cubes-wall camera 256² and the bunny hilbert 64²): indices at 9
// are 5 % smaller than at 5 and 7 % than at 3, at 125 MB/s; 19 gained 5 %
// more for 10× the time. The int16 values are smallest at 5 (1.4 % smaller
// than at 9, 2.6× as fast: 65 against 25 MB/s) — the slower strategies of
// the higher levels find nothing more in them.
constexpr int kIndicesZstdLevel = 9;
constexpr int kDataZstdLevel = 5;

absl::StatusOr<ZarrArray> Create(const std::filesystem::path& store, const char* name, DType t,
                                 int64_t length, int64_t chunk, bool delta = false,
                                 bool shuffle = false, int level = kDefaultZstdLevel) {
  return ZarrArray::Create(store::Path(store, name),
                           {.shape = {length},
                            .chunks = {std::max<int64_t>(1, std::min(length, chunk))},
                            .dtype = t,
                            .zstd_level = level,
                            .delta_filter = delta,
                            .shuffle_filter = shuffle});
}

absl::StatusOr<CscArrays> CreateTransport(const std::filesystem::path& store, int columns,
                                          int64_t nnz) {
  if (absl::Status s = WriteGroup(store::Path(store, store::kTransport)); !s.ok()) return s;
  auto indptr = Create(store, store::kIndptr, DType::kInt64, columns + 1, kColumnChunk);
  // Indices rise inside a column: the delta filter turns them into small
  // numbers zstd packs tighter (DESIGN.md §3), and the byte shuffle puts
  // their mostly-zero high bytes together: 5.1 → 3.3 bits per position on an
  // adaptive cubes-wall store. The int16 values do not gain from a shuffle
  // (adaptive: 6.4 → 6.5 bits), so data has none.
  auto indices =
      Create(store, store::kIndices, DType::kUint32, nnz, kNnzChunk, true, true, kIndicesZstdLevel);
  auto data =
      Create(store, store::kData, DType::kInt16, nnz, kNnzChunk, false, false, kDataZstdLevel);
  auto depth = Create(store, store::kDepth, DType::kUint8, columns, kColumnChunk);
  auto scale = Create(store, store::kScale, DType::kFloat32, columns, kColumnChunk);
  for (const auto* a : {&indptr, &indices, &data, &depth, &scale})
    if (!a->ok()) return a->status();
  return CscArrays{*std::move(indptr), *std::move(indices), *std::move(data), *std::move(depth),
                   *std::move(scale)};
}

// A group's columns quantized (DESIGN.md §1 "Scaling and quantization"):
// the codes, and per column its achieved quantization error energy
// (weighted like the selection) and the bits its largest code needs (0 for
// a column without codes).
struct QuantizedGroup {
  GroupResult result;
  DefaultInitVector<int16_t> q;  // parallel to result.positions, written in full
  std::vector<double> error_energy;
  std::vector<int> bits;
};

absl::StatusOr<QuantizedGroup> QuantizeGroup(const BakeContext& ctx, const StepPlan& steps,
                                             const std::filesystem::path& store,
                                             const FinalizeOptions& options, int g) {
  absl::StatusOr<GroupResult> r = ReadCheckedGroup(ctx.plan, store, options, g);
  if (!r.ok()) return r.status();
  const JobPlan& plan = ctx.plan;
  QuantizedGroup out;
  out.q.resize(r->positions.size());
  std::vector<uint8_t> levels;
  size_t at = 0;
  for (size_t c = 0; c < r->columns.size(); ++c) {
    const GroupColumn& gc = r->columns[c];
    const int m = r->first_column + static_cast<int>(c);
    const auto positions = std::span<const uint32_t>(r->positions).subspan(at, gc.kept);
    const auto values = std::span<const float>(r->values).subspan(at, gc.kept);
    const auto q = std::span(out.q).subspan(at, gc.kept);
    at += gc.kept;
    const std::vector<uint8_t>& level_map = SubbandLevels(plan.width, plan.height, gc.depth);
    levels.resize(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) levels[i] = level_map[positions[i]];
    const std::vector<float>& w =
        SynthesisNormsRef(ctx.params.column_filter, plan.width, plan.height, gc.depth);
    out.error_energy.push_back(QuantizeWithError(values, positions, levels,
                                                 ctx.params.level_scaling, steps.steps[m],
                                                 steps.max_code, ctx.params.seed, m, w, q));
    int largest = 0;
    for (int16_t v : q) largest = std::max(largest, std::abs(int{v}));
    out.bits.push_back(positions.empty() ? 0 : BitsForCode(largest));
  }
  out.result = *std::move(r);
  return out;
}

// Pass 2: groups in order → the CSC arrays. Groups are read and quantized on
// FINALIZE's threads, a few at a time, and appended here in order.
absl::Status WriteTransport(const BakeContext& ctx, const std::filesystem::path& store,
                            const StepPlan& steps, int64_t nnz, const FinalizeOptions& options,
                            StoreStats* stats) {
  const JobPlan& plan = ctx.plan;
  absl::StatusOr<CscArrays> arrays = CreateTransport(store, plan.columns, nnz);
  if (!arrays.ok()) return arrays.status();
  const int threads = Threads(options);
  ArrayAppender<uint32_t> indices(arrays->indices, threads);
  ArrayAppender<int16_t> data(arrays->data, threads);
  std::vector<int64_t> indptr(plan.columns + 1, 0);
  std::vector<uint8_t> depth(plan.columns, 0);
  std::vector<float> scale(plan.columns, 0.0f);
  absl::Status appended = OrderedParallel<QuantizedGroup>(
      plan.groups, threads, threads + 1,
      [&](int g) { return QuantizeGroup(ctx, steps, store, options, g); },
      [&](int, QuantizedGroup& qg) -> absl::Status {
        const GroupResult& r = qg.result;
        if (absl::Status s = indices.Append(r.positions); !s.ok()) return s;
        if (absl::Status s = data.Append(qg.q); !s.ok()) return s;
        for (size_t c = 0; c < r.columns.size(); ++c) {
          const GroupColumn& gc = r.columns[c];
          const int m = r.first_column + static_cast<int>(c);
          indptr[m + 1] = indptr[m] + gc.kept;
          depth[m] = gc.depth;
          scale[m] = steps.steps[m];
          stats->Add({.column = m,
                      .depth = gc.depth,
                      .kept = gc.kept,
                      .energy = gc.energy,
                      .reference_energy = gc.reference_energy,
                      .dropped_energy = gc.dropped_energy,
                      .quantization_energy = qg.error_energy[c],
                      .min_bits = gc.min_bits,
                      .bits = qg.bits[c]});
        }
        return absl::OkStatus();
      });
  if (!appended.ok()) return appended;
  for (absl::Status s :
       {indices.Close(), data.Close(), arrays->indptr.WriteAll<int64_t>(indptr),
        arrays->depth.WriteAll<uint8_t>(depth), arrays->scale.WriteAll<float>(scale)}) {
    if (!s.ok()) return s;
  }
  return WriteAttrs(store::Path(store, store::kTransport),
                    {{"encoding-type", "csc_matrix"},
                     {"encoding-version", "0.1.0"},
                     {"shape", {int64_t{plan.width} * plan.height, plan.columns}}});
}

// A finished store whose staging is gone: a retried FINALIZE has nothing to do.
bool AlreadyFinalized(const std::filesystem::path& store) {
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(store);
  return attrs.ok() && attrs->value("format", "") == store::kFormat;
}

}  // namespace

// Renamed away first (atomic), so a crash midway never leaves a half-deleted
// staging/ that looks like an unfinished job.
absl::Status DropStaging(const std::filesystem::path& store) {
  const std::filesystem::path trash = store / ".staging.removing";
  std::error_code ec;
  if (std::filesystem::exists(store::Path(store, store::kStaging))) {
    std::filesystem::remove_all(trash, ec);
    std::filesystem::rename(store::Path(store, store::kStaging), trash, ec);
    if (ec)
      return absl::InternalError(
          absl::StrCat(store.string(), ": cannot drop staging: ", ec.message()));
  }
  std::filesystem::remove_all(trash, ec);
  if (ec) return absl::InternalError(absl::StrCat(trash.string(), ": ", ec.message()));
  return absl::OkStatus();
}

absl::Status Finalize(const BakeContext& ctx, const std::filesystem::path& store,
                      const FinalizeOptions& options) {
  if (!std::filesystem::exists(store::Path(store, store::kStaging))) {
    if (AlreadyFinalized(store)) return DropStaging(store);
    return absl::FailedPreconditionError(absl::StrCat(store.string(), ": no staging to finalize"));
  }
  const JobPlan& plan = ctx.plan;
  GroupScan scan;
  if (absl::Status s = ScanGroups(plan, store, options, &scan); !s.ok()) return s;
  const int64_t nnz = scan.nnz;
  const StepPlan steps = PlanSteps(scan.columns, ctx.params);

  StoreStats stats(plan.light_res, MaxDepth(plan.width, plan.height));
  if (absl::Status s = WriteTransport(ctx, store, steps, nnz, options, &stats); !s.ok()) return s;
  if (absl::Status s = WriteSamples(store, ctx.samples); !s.ok()) return s;
  // Uniform auto has no single b: "bits" is the widest column's.
  const ManifestBits bits{.bits = steps.bits != 0 ? steps.bits : std::max(2, stats.max_bits()),
                          .bits_needed = steps.bits_needed,
                          .max_column_bits = steps.max_column_bits};

  // Nothing but the store's own files, even where a killed worker left a temp
  // file; removed before the sizes are counted (StoreBytes also skips temp
  // files a stale writer may still be creating).
  if (absl::Status s = RemoveAbandonedTempFiles(store); !s.ok()) return s;
  nlohmann::json stats_json = stats.ToJson();
  stats_json["bytes"] = StoreBytes(ctx, store);
  stats_json["quantization"] = {{"step", steps.step},
                                {"max_code", steps.max_code},
                                {"overflow_columns", steps.overflow_columns},
                                {"expected_energy", steps.expected_energy},
                                {"budget", steps.budget}};
  // The manifest is written last: its presence marks a complete store.
  if (absl::Status s = WriteGroup(store); !s.ok()) return s;
  nlohmann::json manifest = StoreManifest(ctx, bits, std::move(stats_json));
  if (absl::Status s = AddBounceRecord(ctx, store, manifest); !s.ok()) return s;
  if (absl::Status s = WriteAttrs(store, manifest); !s.ok()) return s;
  return options.keep_staging ? absl::OkStatus() : DropStaging(store);
}

}  // namespace wavebake
