// The column stage (TRANSFORM_COLUMNS × groups, then FINALIZE) on a real
// job traced by brute force, K=4, 32×32 tiles and the plan's column groups —
// --case=sphere-plane (default: camera 64×64, N=16, M = 1536), bunny
// (hilbert 64×64, N=32) or cubes-wall (camera 256×256, N=64) — beside, in
// the same run:
//   * the I/O floor: reading the same staging chunks (file read + zstd
//     decompression + checksum) and scattering them into column images
//     (memcpy), with no transform;
//   * the brute-force trace of the same job (BAKE_TILE × tiles, one thread;
//     the median of three when one takes under 10 s of CPU), for the ratio
//     column stage / trace (target ≤ 0.25 on bunny and cubes-wall).
//
//   build/bench_column_stage [--case=bunny] --benchmark_repetitions=3
//                            --benchmark_report_aggregates_only=true
//
// BM_ColumnStage/threads:T is the whole column stage as a rerun on the kept
// trace (worker/tiles/recode.h) with T TRANSFORM_COLUMNS tasks at a time:
// x_trace_cpu = its CPU time (all threads) / the trace's, x_trace = its wall
// time / (the one-thread trace's wall time / T), the trace divided evenly.
//
// All single-threaded. Counters: columns/s, staging MB/s (float32 bytes read;
// rates per CPU second, Google Benchmark's default), x_io = wall time over the
// I/O floor's, x_bake = wall time over the bake's, and x_io_cpu / x_bake_cpu
// the same with thread CPU time (steadier on a shared machine; the wall
// ratios include fsync waits and other processes).
// BM_Finalize reports transport/indices bytes with and without the delta
// filter (DESIGN.md §3), the bits --bits auto chose and the achieved
// per-column error (mean, max of sqrt(dropped + quantization)/sqrt(E_ref)).
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "storage/zarr/zarr_array.h"
#include "worker/columns/finalize.h"
#include "worker/columns/store_manifest.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/recode.h"
#include "worker/tiles/staging.h"

namespace wavebake {

[[noreturn]] void Die(const std::string& what) {
  std::fprintf(stderr, "bench_column_stage: %s\n", what.c_str());
  std::exit(1);
}

double ThreadCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

void Check(const absl::Status& s) {
  if (!s.ok()) Die(s.ToString());
}

double ProcessCpuSeconds() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec +
         1e-6 * u.ru_stime.tv_usec;
}

struct Case {
  std::string name, scene, layout;
  int light_res;
};

const Case kCases[] = {
    {"sphere-plane", "builtin:sphere-plane", "camera:64x64", 16},
    {"bunny", std::string(WB_SHARED_DATA) + "/models/bunny.obj", "hilbert:64x64", 32},
    {"cubes-wall", "builtin:cubes-wall", "camera:256x256", 64},
};
Case g_case = kCases[0];

std::unique_ptr<BakeContext> MakeContext(ColumnMode mode) {
  BakeParams p;
  p.light_res = g_case.light_res;
  p.supersample = 4;
  p.layout = g_case.layout;
  p.column_mode = mode;
  p.refine = false;  // the ratio's baseline is brute force's trace
  absl::StatusOr<std::unique_ptr<BakeContext>> made = MakeBakeContext(g_case.scene, p);
  if (!made.ok()) Die(made.status().ToString());
  return *std::move(made);
}

struct Fixture {
  std::unique_ptr<BakeContext> ctx = MakeContext(ColumnMode::kAdaptive);
  std::filesystem::path store = std::filesystem::temp_directory_path() /
                                ("wavebake-bench-columns-" + std::to_string(::getpid()));
  double bake_seconds = 0, bake_cpu_seconds = 0;  // the whole BAKE_TILE phase, one thread (medians)
  double io_seconds = 0, io_cpu_seconds = 0;      // the I/O floor of all groups (BM_StagingIo)

  // The trace is every ratio's denominator, so a short one (the bunny's,
  // ~1 s) is timed three times and its medians kept: single traces of the
  // same job varied by a third between processes on a shared machine.
  Fixture() {
    Check(CreateStaging(ctx->plan, store, TraceRecord(*ctx)));
    std::vector<double> wall, cpu;
    do {
      const auto start = std::chrono::steady_clock::now();
      const double cpu_start = ThreadCpuSeconds();
      for (int t = 0; t < ctx->plan.tiles(); ++t) Check(BakeTile(*ctx, store, t, nullptr));
      cpu.push_back(ThreadCpuSeconds() - cpu_start);
      wall.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    } while (cpu.size() < 3 && cpu[0] < kRepeatTracesUnder);
    bake_cpu_seconds = Median(cpu);
    bake_seconds = Median(wall);
  }
  static constexpr double kRepeatTracesUnder = 10;  // seconds of CPU
  static double Median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  }
  ~Fixture() {
    std::error_code ec;
    std::filesystem::remove_all(store, ec);
  }
  uint64_t StagingFloatBytes() const {
    return uint64_t(ctx->plan.groups) * ctx->plan.tiles() * ctx->plan.group_size *
           ctx->plan.tile_cells() * sizeof(float);
  }
};

Fixture& GetFixture() {
  static Fixture fixture;
  return fixture;
}

void SetRates(benchmark::State& state, const Fixture& f) {
  state.counters["columns/s"] = benchmark::Counter(double(f.ctx->plan.columns) * state.iterations(),
                                                   benchmark::Counter::kIsRate);
  state.counters["staging_MB/s"] = benchmark::Counter(
      double(f.StagingFloatBytes()) * state.iterations() / 1e6, benchmark::Counter::kIsRate);
}

// The I/O floor: every chunk of every group read, decompressed and scattered
// into column images, exactly as TRANSFORM_COLUMNS assembles them.
void BM_StagingIo(benchmark::State& state) {
  Fixture& f = GetFixture();
  const JobPlan& plan = f.ctx->plan;
  absl::StatusOr<ZarrArray> staging =
      ZarrArray::Open(store::Path(f.store, store::kStagingTransport));
  if (!staging.ok()) Die(staging.status().ToString());
  std::vector<float> chunk(size_t(plan.group_size) * plan.tile_cells());
  std::vector<float> images(size_t(plan.group_size) * plan.width * plan.height);
  double seconds = 0, cpu = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = ThreadCpuSeconds();
    for (int g = 0; g < plan.groups; ++g) {
      for (int t = 0; t < plan.tiles(); ++t) {
        const int64_t index[2] = {g, t};
        Check(staging->ReadChunkInto(index, std::as_writable_bytes(std::span(chunk))));
        const TileRect r = plan.Tile(t);
        for (int c = 0; c < plan.GroupCount(g); ++c) {
          for (int y = 0; y < r.height; ++y) {
            std::copy_n(chunk.data() + size_t(c) * plan.tile_cells() + y * r.width, r.width,
                        images.data() + size_t(c) * plan.width * plan.height +
                            size_t(r.y0 + y) * plan.width + r.x0);
          }
        }
      }
    }
    benchmark::DoNotOptimize(images.data());
    cpu += ThreadCpuSeconds() - cpu_start;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  f.io_seconds = seconds / state.iterations();
  f.io_cpu_seconds = cpu / state.iterations();
  SetRates(state, f);
}
BENCHMARK(BM_StagingIo)->Unit(benchmark::kMillisecond);

// TRANSFORM_COLUMNS over every group, one thread, per column mode.
void BM_TransformColumns(benchmark::State& state) {
  Fixture& f = GetFixture();
  const auto mode = static_cast<ColumnMode>(state.range(0));
  const std::unique_ptr<BakeContext> ctx = MakeContext(mode);
  double seconds = 0, cpu = 0;
  uint64_t kept = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = ThreadCpuSeconds();
    kept = 0;
    for (int g = 0; g < ctx->plan.groups; ++g) {
      GroupStats stats;
      Check(TransformColumns(*ctx, f.store, g, &stats));
      kept += stats.kept;
    }
    cpu += ThreadCpuSeconds() - cpu_start;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  seconds /= state.iterations();
  cpu /= state.iterations();
  SetRates(state, f);
  state.counters["kept"] = double(kept);
  if (f.io_seconds > 0) state.counters["x_io"] = seconds / f.io_seconds;
  if (f.io_cpu_seconds > 0) state.counters["x_io_cpu"] = cpu / f.io_cpu_seconds;
  state.counters["x_bake"] = seconds / f.bake_seconds;
  state.counters["x_bake_cpu"] = cpu / f.bake_cpu_seconds;
  state.counters["bake_cpu_s"] = f.bake_cpu_seconds;
  state.SetLabel(mode == ColumnMode::k2d ? "2d" : mode == ColumnMode::kFull ? "full" : "adaptive");
}
BENCHMARK(BM_TransformColumns)
    ->Arg(int(ColumnMode::k2d))
    ->Arg(int(ColumnMode::kFull))
    ->Arg(int(ColumnMode::kAdaptive))
    ->Unit(benchmark::kMillisecond);

// The whole column stage, as a rerun on the kept trace: what a bake spends
// after its trace.
void BM_ColumnStage(benchmark::State& state) {
  Fixture& f = GetFixture();
  const int threads = state.range(0);
  const auto out = f.store.string() + "-recoded";
  double seconds = 0, cpu = 0;
  for (auto _ : state) {
    std::filesystem::remove_all(out);
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = ProcessCpuSeconds();
    Check(Recode(*f.ctx, f.store, out, {.threads = threads}));
    cpu += ProcessCpuSeconds() - cpu_start;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  std::filesystem::remove_all(out);
  seconds /= state.iterations();
  cpu /= state.iterations();
  state.counters["x_trace"] = seconds / (f.bake_seconds / threads);
  state.counters["x_trace_cpu"] = cpu / f.bake_cpu_seconds;
  state.counters["cpu_s"] = cpu;
  state.counters["trace_cpu_s"] = f.bake_cpu_seconds;
  state.SetLabel(g_case.name);
}
BENCHMARK(BM_ColumnStage)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// FINALIZE (staging kept so it can repeat), after an adaptive column pass.
void BM_Finalize(benchmark::State& state) {
  Fixture& f = GetFixture();
  for (int g = 0; g < f.ctx->plan.groups; ++g) Check(TransformColumns(*f.ctx, f.store, g, nullptr));
  for (auto _ : state) Check(Finalize(*f.ctx, f.store, {.keep_staging = true}));
  // The same indices without the delta filter, for the record.
  absl::StatusOr<ZarrArray> indices = ZarrArray::Open(store::Path(f.store, store::kIndices));
  if (!indices.ok()) Die(indices.status().ToString());
  absl::StatusOr<std::vector<uint32_t>> values = indices->ReadAll<uint32_t>();
  if (!values.ok()) Die(values.status().ToString());
  ArraySpec plain = indices->spec();
  plain.delta_filter = false;
  const auto plain_dir = f.store / "bench_indices_plain";
  std::error_code ec;
  std::filesystem::remove_all(plain_dir, ec);
  absl::StatusOr<ZarrArray> copy = ZarrArray::Create(plain_dir, plain);
  if (!copy.ok()) Die(copy.status().ToString());
  Check(copy->WriteAll<uint32_t>(*values));
  state.counters["nnz"] = double(values->size());
  state.counters["indices_bytes_delta"] = double(DirectoryBytes(indices->dir()));
  state.counters["indices_bytes_plain"] = double(DirectoryBytes(plain_dir));
  state.counters["data_bytes"] = double(DirectoryBytes(store::Path(f.store, store::kData)));
  state.counters["raw_MB"] = double(f.ctx->samples.size()) * f.ctx->plan.columns * 4 / 1e6;
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(f.store);
  if (!info.ok()) Die(info.status().ToString());
  const nlohmann::json& stats = info->attrs["stats"];
  state.counters["bits"] = info->bits;
  std::fprintf(stderr, "manifest stats: %s\n", stats.dump().c_str());
  state.counters["transport_bytes"] = stats["bytes"]["transport"].get<double>();
  state.counters["err_mean"] = stats["column_error"]["mean"].get<double>();
  state.counters["err_max"] = stats["column_error"]["max"].get<double>();
}
BENCHMARK(BM_Finalize)->Unit(benchmark::kMillisecond);

}  // namespace wavebake

int main(int argc, char** argv) {
  // --case=NAME, ours; the rest is Google Benchmark's.
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--case=", 0) != 0) {
      rest.push_back(argv[i]);
      continue;
    }
    bool found = false;
    for (const wavebake::Case& c : wavebake::kCases) {
      if (arg.substr(7) == c.name) wavebake::g_case = c, found = true;
    }
    if (!found) wavebake::Die("--case: sphere-plane, bunny or cubes-wall");
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
