#include "worker/columns/finalize_parts.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "absl/strings/str_cat.h"
#include "core/columns/column_coding.h"
#include "core/columns/quantizer.h"
#include "core/wavelets/subband.h"
#include "core/wavelets/wavelet2d.h"
#include "storage/files/atomic_file.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_group.h"
#include "worker/loop/ordered_parallel.h"

namespace wavebake {
namespace {

// Chunk lengths of the final arrays: ~1 MB of indices, 512 KB of data.
constexpr int64_t kNnzChunk = 1 << 18;
constexpr int64_t kColumnChunk = 1 << 16;

// zstd levels of the nnz-long arrays (zstd 1.5.4, measured on the N=64
// stores of cubes-wall camera 256² and the bunny hilbert 64²): indices at 9
// are 5 % smaller than at 5 and 7 % than at 3, at 125 MB/s; 19 gained 5 %
// more for 10× the time. The int16 values are smallest at 5 (1.4 % smaller
// than at 9, 2.6× as fast: 65 against 25 MB/s) — the slower strategies of
// the higher levels find nothing more in them.
constexpr int kIndicesZstdLevel = 9;
// Level 9's lazy2 search, narrowed: matches of at least 6 bytes, 2^16-entry
// hash and chain tables, 8 candidates per position: −1.5 % to +0.3 % of
// level 9's indices bytes on six stores (N = 16–64), at 1.6–1.9× its speed
// on the three timed (`zstd -b9 -B1048576 --zstd=...` on their decoded
// chunks; docs/RESULTS.md).
constexpr ZstdSearch kIndicesZstdSearch = {
    .strategy = 5, .min_match = 6, .chain_log = 16, .hash_log = 16, .search_log = 3};
constexpr int kDataZstdLevel = 5;

absl::Status CheckGroup(const JobPlan& plan, const std::filesystem::path& store, int g,
                        const GroupResult& r) {
  if (r.first_column == plan.GroupFirst(g) &&
      r.columns.size() == static_cast<size_t>(plan.GroupCount(g))) {
    return absl::OkStatus();
  }
  return absl::DataLossError(
      absl::StrCat(GroupResultPath(store, g).string(), ": columns do not match the job plan"));
}

absl::Status Stopped(const FinalizeOptions& options, int group) {
  if (options.cancel == nullptr || !options.cancel->load()) return absl::OkStatus();
  return absl::CancelledError(absl::StrCat("FINALIZE: cancelled at group ", group));
}

// Group g's result (at least its column table if `columns_only`), checked
// against the plan: held in the job's in-memory staging
// (worker/tiles/memory_staging.h), else read from staging/groups.
// FailedPrecondition if it is in neither (FINALIZE ran too early).
absl::StatusOr<std::shared_ptr<const GroupResult>> ReadCheckedGroup(
    const JobPlan& plan, const std::filesystem::path& store, const FinalizeOptions& options, int g,
    bool columns_only) {
  if (absl::Status s = Stopped(options, g); !s.ok()) return s;
  std::shared_ptr<const GroupResult> held;
  if (options.memory != nullptr)
    if (const std::shared_ptr<MemoryStaging::Job> job = options.memory->Find(store))
      held = job->Group(g);
  if (held == nullptr) {
    absl::StatusOr<GroupResult> r =
        columns_only ? ReadGroupColumns(store, g) : ReadGroupResult(store, g);
    if (absl::IsNotFound(r.status()))
      return absl::FailedPreconditionError(
          absl::StrCat("group ", g, " has not been transformed: ", r.status().message()));
    if (!r.ok()) return r.status();
    held = std::make_shared<const GroupResult>(*std::move(r));
  }
  if (absl::Status s = CheckGroup(plan, store, g, *held); !s.ok()) return s;
  return held;
}

absl::StatusOr<ZarrArray> Create(const std::filesystem::path& store, const char* name, DType t,
                                 int64_t length, int64_t chunk, bool delta = false,
                                 bool shuffle = false, int level = kDefaultZstdLevel,
                                 ZstdSearch search = {}) {
  return ZarrArray::Create(store::Path(store, name),
                           {.shape = {length},
                            .chunks = {std::max<int64_t>(1, std::min(length, chunk))},
                            .dtype = t,
                            .zstd_level = level,
                            .zstd_search = search,
                            .delta_filter = delta,
                            .shuffle_filter = shuffle});
}

// The shard outcome file: "WBQ1", first column and count (int32), then per
// column its error energy (float64) and bits (int32), native byte order
// (written and read by the same build's workers within one job).
constexpr char kOutcomeMagic[4] = {'W', 'B', 'Q', '1'};

}  // namespace

int FinalizeThreads(const FinalizeOptions& options) {
  return options.threads > 0 ? options.threads
                             : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

absl::StatusOr<FinalizeScan> ScanGroups(const JobPlan& plan, const std::filesystem::path& store,
                                        const FinalizeOptions& options) {
  FinalizeScan scan;
  scan.columns.reserve(plan.columns);
  scan.group_offsets.reserve(plan.groups + 1);
  const int threads = FinalizeThreads(options);
  absl::Status s = OrderedParallel<std::shared_ptr<const GroupResult>>(
      plan.groups, threads, 2 * threads,
      [&](int g) { return ReadCheckedGroup(plan, store, options, g, true); },
      [&](int, std::shared_ptr<const GroupResult>& r) {
        scan.group_offsets.push_back(scan.nnz);
        for (const GroupColumn& c : r->columns) scan.nnz += c.kept;
        scan.columns.insert(scan.columns.end(), r->columns.begin(), r->columns.end());
        return absl::OkStatus();
      });
  if (!s.ok()) return s;
  scan.group_offsets.push_back(scan.nnz);
  return scan;
}

StepPlan PlanFinalizeSteps(const FinalizeScan& scan, const BakeParams& params) {
  std::vector<ColumnQuantInput> in;
  in.reserve(scan.columns.size());
  for (const GroupColumn& c : scan.columns) {
    in.push_back({.max_abs = c.max_abs,
                  .step_unit = c.step_unit,
                  .reference_energy = c.reference_energy,
                  .min_bits = c.min_bits});
  }
  return PlanSteps(in, params);
}

ShardPlan MakeShardPlan(const FinalizeScan& scan, const StepPlan& steps) {
  return {.group_offsets = scan.group_offsets, .steps = steps.steps, .max_code = steps.max_code};
}

absl::StatusOr<QuantizedGroup> QuantizeGroup(const BakeContext& ctx, const ShardPlan& steps,
                                             const std::filesystem::path& store,
                                             const FinalizeOptions& options, int g) {
  absl::StatusOr<std::shared_ptr<const GroupResult>> read =
      ReadCheckedGroup(ctx.plan, store, options, g, false);
  if (!read.ok()) return read.status();
  const std::shared_ptr<const GroupResult>& r = *read;
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
  out.result = r;
  return out;
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
  auto indices = Create(store, store::kIndices, DType::kUint32, nnz, kNnzChunk, true, true,
                        kIndicesZstdLevel, kIndicesZstdSearch);
  auto data =
      Create(store, store::kData, DType::kInt16, nnz, kNnzChunk, false, false, kDataZstdLevel);
  auto depth = Create(store, store::kDepth, DType::kUint8, columns, kColumnChunk);
  auto scale = Create(store, store::kScale, DType::kFloat32, columns, kColumnChunk);
  for (const auto* a : {&indptr, &indices, &data, &depth, &scale})
    if (!a->ok()) return a->status();
  return CscArrays{*std::move(indptr), *std::move(indices), *std::move(data), *std::move(depth),
                   *std::move(scale)};
}

std::filesystem::path ShardOutcomePath(const std::filesystem::path& store, int shard) {
  return store::Path(store, store::kStagingFinalize) / absl::StrCat(shard, ".wbq");
}

absl::Status WriteShardOutcome(const std::filesystem::path& store, int shard, int first_column,
                               std::span<const double> error_energy, std::span<const int> bits) {
  const int32_t header[2] = {first_column, static_cast<int32_t>(error_energy.size())};
  std::vector<std::byte> out(sizeof kOutcomeMagic + sizeof header +
                             error_energy.size() * (sizeof(double) + sizeof(int32_t)));
  std::byte* p = out.data();
  const auto put = [&p](const void* src, size_t n) {
    std::memcpy(p, src, n);
    p += n;
  };
  put(kOutcomeMagic, sizeof kOutcomeMagic);
  put(header, sizeof header);
  put(error_energy.data(), error_energy.size_bytes());
  for (int b : bits) {
    const int32_t v = b;
    put(&v, sizeof v);
  }
  const std::filesystem::path path = ShardOutcomePath(store, shard);
  if (absl::Status s = CreateDirectories(path.parent_path()); !s.ok()) return s;
  return AtomicWriteFile(path, out);
}

absl::Status ReadShardOutcome(const std::filesystem::path& store, int shard, int first_column,
                              int count, std::span<double> error_energy, std::span<int> bits) {
  const std::filesystem::path path = ShardOutcomePath(store, shard);
  absl::StatusOr<std::vector<std::byte>> in = ReadFile(path);
  if (absl::IsNotFound(in.status()))
    return absl::FailedPreconditionError(
        absl::StrCat("FINALIZE shard ", shard, " has not finished (no ", path.string(), ")"));
  if (!in.ok()) return in.status();
  int32_t header[2] = {};
  const size_t expected =
      sizeof kOutcomeMagic + sizeof header + size_t(count) * (sizeof(double) + sizeof(int32_t));
  if (in->size() == expected) std::memcpy(header, in->data() + sizeof kOutcomeMagic, sizeof header);
  if (in->size() != expected || std::memcmp(in->data(), kOutcomeMagic, 4) != 0 ||
      header[0] != first_column || header[1] != count) {
    return absl::DataLossError(
        absl::StrCat(path.string(), ": not the outcome of columns ", first_column, "+", count));
  }
  const std::byte* p = in->data() + sizeof kOutcomeMagic + sizeof header;
  std::memcpy(error_energy.data() + first_column, p, size_t(count) * sizeof(double));
  p += size_t(count) * sizeof(double);
  for (int i = 0; i < count; ++i) {
    int32_t v = 0;
    std::memcpy(&v, p + size_t(i) * sizeof v, sizeof v);
    bits[first_column + i] = v;
  }
  return absl::OkStatus();
}

}  // namespace wavebake
