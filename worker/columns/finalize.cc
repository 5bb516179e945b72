#include "worker/columns/finalize.h"

#include <algorithm>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/bake/finalize_shards.h"
#include "core/wavelets/wavelet2d.h"
#include "storage/files/atomic_file.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_samples.h"
#include "storage/zarr/array_appender.h"
#include "storage/zarr/zarr_group.h"
#include "worker/columns/bounce_record.h"
#include "worker/columns/finalize_parts.h"
#include "worker/columns/store_manifest.h"
#include "worker/columns/store_stats.h"
#include "worker/loop/ordered_parallel.h"

namespace wavebake {
namespace {

// A finished store whose staging is gone: a retried FINALIZE task has nothing to do.
bool AlreadyFinalized(const std::filesystem::path& store) {
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(store);
  return attrs.ok() && attrs->value("format", "") == store::kFormat;
}

// OK to go on (staging is there); `done` when the store is finished already.
absl::Status CheckStaging(const std::filesystem::path& store, bool* done) {
  *done = false;
  if (std::filesystem::exists(store::Path(store, store::kStaging))) return absl::OkStatus();
  if (AlreadyFinalized(store)) {
    *done = true;
    return absl::OkStatus();
  }
  return absl::FailedPreconditionError(absl::StrCat(store.string(), ": no staging to finalize"));
}

// Shard `shard`'s chunks: those whose first element lies in its groups'
// elements [e0, e1), i.e. chunks [ceil(e0/C), ceil(e1/C)); their elements
// run to min(end·C, nnz) and may need the groups after the shard's. Groups
// are read and quantized on the task's threads, a few at a time, and
// appended in order; the shard's own groups also give their columns'
// outcome.
absl::Status WriteShard(const BakeContext& ctx, const std::filesystem::path& store,
                        const ShardPlan& steps, int shard, const FinalizeOptions& options) {
  const JobPlan& plan = ctx.plan;
  const int64_t nnz = steps.nnz();
  absl::StatusOr<CscArrays> arrays = CreateTransport(store, plan.columns, nnz);
  if (!arrays.ok()) return arrays.status();
  const int g0 = ShardFirstGroup(plan.groups, shard), g1 = ShardFirstGroup(plan.groups, shard + 1);
  const int64_t chunk = arrays->indices.spec().chunks.at(0);
  const auto& at = steps.group_offsets;
  const int64_t first_chunk = (at[g0] + chunk - 1) / chunk;
  const int64_t end_chunk = (at[g1] + chunk - 1) / chunk;
  const int64_t begin = std::min(first_chunk * chunk, nnz);
  const int64_t end = std::max(begin, std::min(end_chunk * chunk, nnz));
  // Groups to read: the shard's own, and on to the one holding element end − 1.
  int g_end = g1;
  if (end > begin) {
    const int holding_last =
        static_cast<int>(std::upper_bound(at.begin(), at.end(), end - 1) - at.begin()) - 1;
    g_end = std::max(g_end, holding_last + 1);
  }
  const int threads = FinalizeThreads(options);
  ArrayAppender<uint32_t> indices(arrays->indices, threads, first_chunk, end - begin);
  ArrayAppender<int16_t> data(arrays->data, threads, first_chunk, end - begin);
  std::vector<double> error_energy;
  std::vector<int> bits;
  absl::Status appended = OrderedParallel<QuantizedGroup>(
      g_end - g0, threads, threads + 1,
      [&](int i) { return QuantizeGroup(ctx, steps, store, options, g0 + i); },
      [&](int i, QuantizedGroup& qg) -> absl::Status {
        const int g = g0 + i;
        if (g < g1) {
          error_energy.insert(error_energy.end(), qg.error_energy.begin(), qg.error_energy.end());
          bits.insert(bits.end(), qg.bits.begin(), qg.bits.end());
        }
        // The part of the group's elements [at[g], at[g+1]) this shard writes.
        const int64_t from = std::max(at[g], begin), to = std::min(at[g + 1], end);
        if (from >= to) return absl::OkStatus();
        const size_t offset = static_cast<size_t>(from - at[g]), n = static_cast<size_t>(to - from);
        if (absl::Status s =
                indices.Append(std::span<const uint32_t>(qg.result->positions).subspan(offset, n));
            !s.ok())
          return s;
        return data.Append(std::span<const int16_t>(qg.q).subspan(offset, n));
      });
  if (!appended.ok()) return appended;
  for (absl::Status s : {indices.Close(), data.Close()})
    if (!s.ok()) return s;
  return WriteShardOutcome(store, shard, plan.GroupFirst(g0), error_energy, bits);
}

// The column arrays and the transport attributes, from the scan, the steps
// and the shards' outcomes; the stats in column order (as one task added
// them: StoreStats sums in that order).
absl::Status WriteColumns(const BakeContext& ctx, const std::filesystem::path& store,
                          const FinalizeScan& scan, const StepPlan& steps, StoreStats* stats) {
  const JobPlan& plan = ctx.plan;
  absl::StatusOr<CscArrays> arrays = CreateTransport(store, plan.columns, scan.nnz);
  if (!arrays.ok()) return arrays.status();
  std::vector<double> error_energy(plan.columns, 0.0);
  std::vector<int> bits(plan.columns, 0);
  for (int k = 0; k < FinalizeShards(plan.groups); ++k) {
    const int first = plan.GroupFirst(ShardFirstGroup(plan.groups, k));
    const int end_group = ShardFirstGroup(plan.groups, k + 1);
    const int end = end_group < plan.groups ? plan.GroupFirst(end_group) : plan.columns;
    if (absl::Status s = ReadShardOutcome(store, k, first, end - first, error_energy, bits);
        !s.ok())
      return s;
  }
  std::vector<int64_t> indptr(plan.columns + 1, 0);
  std::vector<uint8_t> depth(plan.columns, 0);
  std::vector<float> scale(plan.columns, 0.0f);
  for (int m = 0; m < plan.columns; ++m) {
    const GroupColumn& gc = scan.columns[m];
    indptr[m + 1] = indptr[m] + gc.kept;
    depth[m] = gc.depth;
    scale[m] = steps.steps[m];
    stats->Add({.column = m,
                .depth = gc.depth,
                .kept = gc.kept,
                .energy = gc.energy,
                .reference_energy = gc.reference_energy,
                .dropped_energy = gc.dropped_energy,
                .quantization_energy = error_energy[m],
                .min_bits = gc.min_bits,
                .bits = bits[m]});
  }
  for (absl::Status s :
       {arrays->indptr.WriteAll<int64_t>(indptr), arrays->depth.WriteAll<uint8_t>(depth),
        arrays->scale.WriteAll<float>(scale)}) {
    if (!s.ok()) return s;
  }
  return WriteAttrs(store::Path(store, store::kTransport),
                    {{"encoding-type", "csc_matrix"},
                     {"encoding-version", "0.1.0"},
                     {"shape", {int64_t{plan.width} * plan.height, plan.columns}}});
}

absl::Status WriteStore(const BakeContext& ctx, const std::filesystem::path& store,
                        const FinalizeScan& scan, const StepPlan& steps) {
  const JobPlan& plan = ctx.plan;
  StoreStats stats(plan.light_res, MaxDepth(plan.width, plan.height));
  if (absl::Status s = WriteColumns(ctx, store, scan, steps, &stats); !s.ok()) return s;
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
  return WriteAttrs(store, manifest);
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

absl::Status FinalizeShard(const BakeContext& ctx, const std::filesystem::path& store, int shard,
                           const FinalizeOptions& options) {
  if (shard < 0 || shard >= FinalizeShards(ctx.plan.groups)) {
    return absl::InvalidArgumentError(absl::StrCat("FINALIZE shard ", shard, " is not in 0..",
                                                   FinalizeShards(ctx.plan.groups) - 1));
  }
  bool done = false;
  if (absl::Status s = CheckStaging(store, &done); !s.ok() || done) return s;
  absl::StatusOr<ShardPlan> steps = ReadShardPlan(store, ctx.plan);
  if (absl::IsNotFound(steps.status()) || absl::IsDataLoss(steps.status())) {
    absl::StatusOr<FinalizeScan> scan = ScanGroups(ctx.plan, store, options);
    if (!scan.ok()) return scan.status();
    steps = MakeShardPlan(*scan, PlanFinalizeSteps(*scan, ctx.params));
    if (absl::Status s = WriteShardPlan(store, *steps); !s.ok()) return s;
  }
  if (!steps.ok()) return steps.status();
  return WriteShard(ctx, store, *steps, shard, options);
}

absl::Status FinalizeStore(const BakeContext& ctx, const std::filesystem::path& store,
                           const FinalizeOptions& options) {
  bool done = false;
  if (absl::Status s = CheckStaging(store, &done); !s.ok()) return s;
  if (!done) {
    absl::StatusOr<FinalizeScan> scan = ScanGroups(ctx.plan, store, options);
    if (!scan.ok()) return scan.status();
    const StepPlan steps = PlanFinalizeSteps(*scan, ctx.params);
    if (absl::Status s = WriteStore(ctx, store, *scan, steps); !s.ok()) return s;
  }
  // The job's staging chunks held in memory go with its staging/.
  if (options.memory) options.memory->Drop(store);
  return options.keep_staging && !done ? absl::OkStatus() : DropStaging(store);
}

absl::Status Finalize(const BakeContext& ctx, const std::filesystem::path& store,
                      const FinalizeOptions& options) {
  bool done = false;
  if (absl::Status s = CheckStaging(store, &done); !s.ok()) return s;
  if (done) return DropStaging(store);
  absl::StatusOr<FinalizeScan> scan = ScanGroups(ctx.plan, store, options);
  if (!scan.ok()) return scan.status();
  const StepPlan steps = PlanFinalizeSteps(*scan, ctx.params);
  const ShardPlan shards = MakeShardPlan(*scan, steps);
  for (int k = 0; k < FinalizeShards(ctx.plan.groups); ++k) {
    if (absl::Status s = WriteShard(ctx, store, shards, k, options); !s.ok()) return s;
  }
  if (absl::Status s = WriteStore(ctx, store, *scan, steps); !s.ok()) return s;
  if (options.memory) options.memory->Drop(store);
  return options.keep_staging ? absl::OkStatus() : DropStaging(store);
}

}  // namespace wavebake
