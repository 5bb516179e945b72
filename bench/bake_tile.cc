// One BAKE_TILE task (worker/tiles/bake_tile.h) on builtin:sphere-plane — camera
// layout 64×64, N=32, K=4, the default 32×32 tile and the plan's column groups —
// beside, in the same run, the pure tracing cost of the same tile: the row
// tracer alone for the same samples (no row transform, no transpose, no
// store), and tracing plus the row transform. The tile is the one with the
// most samples. /refine:1 traces by visibility refinement (the default),
// /refine:0 by brute force.
//
//   build/bench_bake_tile --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// rays/s counts the rays handed to Embree. BM_BakeTile's "x_trace" is its
// wall-clock time per tile over BM_TraceOnly's (run first), "x_trace_cpu" the
// same with thread CPU time: the overhead of everything in the task that is
// not tracing (target: close to 1, tracing dominates). The two differ by the
// time the store writes wait for fsync (and by CPU contention on a shared
// machine). Benchmark times are wall-clock.
#include "worker/tiles/bake_tile.h"

#include <benchmark/benchmark.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/transport/refined_row.h"
#include "core/transport/transport_row.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/row_transform.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

[[noreturn]] void Die(const std::string& what) {
  std::fprintf(stderr, "bench_bake_tile: %s\n", what.c_str());
  std::exit(1);
}

struct Fixture {
  std::unique_ptr<BakeContext> ctx;
  std::filesystem::path store;
  int tile = 0;
  std::vector<int32_t> samples;  // ids of the tile's samples, in cell order
  // Per tile, set by BM_TraceOnly and read by BM_BakeTile.
  double trace_wall_seconds = 0, trace_cpu_seconds = 0;

  explicit Fixture(bool refine) {
    BakeParams p;
    p.light_res = 32;
    p.supersample = 4;
    p.layout = "camera";
    p.refine = refine;
    absl::StatusOr<std::unique_ptr<BakeContext>> made = MakeBakeContext("builtin:sphere-plane", p);
    if (!made.ok()) Die(made.status().ToString());
    ctx = *std::move(made);
    store = std::filesystem::temp_directory_path() /
            ("wavebake-bench-bake-tile-" + std::to_string(::getpid()) + (refine ? "-r" : "-b"));
    if (absl::Status s = CreateStaging(ctx->plan, store); !s.ok()) Die(s.ToString());
    size_t most = 0;
    for (int t = 0; t < ctx->plan.tiles(); ++t) {
      std::vector<int32_t> ids = TileSamples(t);
      if (ids.size() > most) most = ids.size(), tile = t, samples = std::move(ids);
    }
  }
  ~Fixture() {
    std::error_code ec;
    std::filesystem::remove_all(store, ec);
  }

  std::vector<int32_t> TileSamples(int t) const {
    const TileRect r = ctx->plan.Tile(t);
    std::vector<int32_t> ids;
    for (int y = r.y0; y < r.y0 + r.height; ++y) {
      for (int x = r.x0; x < r.x0 + r.width; ++x) {
        const int32_t id = ctx->samples.grid[y * ctx->samples.width + x];
        if (id >= 0) ids.push_back(id);
      }
    }
    return ids;
  }
};

Fixture& GetFixture(bool refine) {
  static Fixture brute(false), refined(true);  // built once, shared by all benchmarks
  return refine ? refined : brute;
}

// Wall-clock and this thread's CPU seconds since construction.
struct Stopwatch {
  static double CpuNow() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
  }
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = CpuNow();
  double WallSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  }
  double CpuSeconds() const { return CpuNow() - cpu; }
};

void SetCounters(benchmark::State& state, uint64_t rays, size_t samples) {
  state.counters["rays/s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["samples"] = static_cast<double>(samples);
}

// Tracing (and, with row_transform, the row transform) of the tile's rows.
void TraceTile(benchmark::State& state, bool row_transform) {
  Fixture& f = GetFixture(state.range(0) != 0);
  const BakeContext& ctx = *f.ctx;
  std::vector<float> row(ctx.plan.columns);
  TransportStats stats;
  RefineScratch scratch;
  double wall = 0, cpu = 0;
  for (auto _ : state) {
    const Stopwatch watch;
    for (int32_t id : f.samples) {
      if (ctx.refine) {
        RefinedTransportRow(ctx.caster, ctx.cubemap, ctx.jitter, *ctx.refine,
                            ctx.samples.position[id], ctx.samples.normal[id], ctx.epsilon, row,
                            &stats, scratch);
      } else {
        TransportRow(ctx.caster, ctx.cubemap, ctx.jitter, ctx.samples.position[id],
                     ctx.samples.normal[id], ctx.epsilon, row, &stats);
      }
      if (row_transform) RowTransform(ctx.params.row_filter, ctx.plan.light_res, row);
      benchmark::DoNotOptimize(row.data());
    }
    wall += watch.WallSeconds();
    cpu += watch.CpuSeconds();
  }
  if (!row_transform) {
    f.trace_wall_seconds = wall / state.iterations();
    f.trace_cpu_seconds = cpu / state.iterations();
  }
  SetCounters(state, stats.rays_traced, f.samples.size());
}

void BM_TraceOnly(benchmark::State& state) { TraceTile(state, false); }
BENCHMARK(BM_TraceOnly)
    ->ArgName("refine")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_TraceAndRowTransform(benchmark::State& state) { TraceTile(state, true); }
BENCHMARK(BM_TraceAndRowTransform)
    ->ArgName("refine")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_BakeTile(benchmark::State& state) {
  const Fixture& f = GetFixture(state.range(0) != 0);
  TileStats stats;
  double wall = 0, cpu = 0;
  for (auto _ : state) {
    const Stopwatch watch;
    if (absl::Status s = BakeTile(*f.ctx, f.store, f.tile, &stats); !s.ok()) {
      state.SkipWithError(s.ToString().c_str());
      return;
    }
    wall += watch.WallSeconds();
    cpu += watch.CpuSeconds();
  }
  SetCounters(state, stats.rays_traced, f.samples.size());
  state.counters["MB_written"] =
      static_cast<double>(stats.bytes_written) / state.iterations() / 1e6;
  if (f.trace_wall_seconds > 0 && f.trace_cpu_seconds > 0) {
    state.counters["x_trace"] = wall / state.iterations() / f.trace_wall_seconds;
    state.counters["x_trace_cpu"] = cpu / state.iterations() / f.trace_cpu_seconds;
  }
}
BENCHMARK(BM_BakeTile)
    ->ArgName("refine")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
