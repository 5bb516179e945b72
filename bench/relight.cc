// Relighting frame rate (runtime/relight/relighter.h, Eq. 8 of the 4D paper) at 128²
// and 256² samples with 64, 256 and 1024 wavelet lights of grace.hdr, one
// core, beside the dense T·L of the same matrix (runtime/reference/relight_oracles.h
// DenseRelight over all 6N² columns) in the same run. `x_dense` is the dense
// frame time over the Eq. 8 frame time (both thread CPU time).
//
// The matrix is synthetic with a realistic sparsity: light_res 32 (M = 6144
// columns), every column keeps 2 % of the grid's cells (nnz/column = 328 at
// 128², 1311 at 256²) at uniform random positions, depth uniform in
// 0..log2(W), Haar columns. The dense matrix of 256² is 1.6 GB. (Real stores
// for comparison, camera:64x64, N = 32, target 1 %: disk-over-plane keeps
// 1.75 % of the cells per column, cubes-wall 4.7 %.)
//   ./build/bench_relight --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include "core/wavelets/wavelet2d.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/relight_oracles.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/relighter.h"
#include "runtime/relight/row_basis.h"

namespace wavebake {
namespace {

constexpr int kLightRes = 32;
constexpr double kKeptFraction = 0.02;

double ThreadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

CompressedColumns SyntheticColumns(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  CompressedColumns t;
  t.width = t.height = n;
  t.light_res = kLightRes;
  t.columns = 6 * kLightRes * kLightRes;
  const int cells = n * n, nnz = static_cast<int>(kKeptFraction * cells);
  std::uniform_int_distribution<uint32_t> pos(0, cells - 1);
  std::uniform_int_distribution<int> depth(0, MaxDepth(n, n));
  std::normal_distribution<float> value(0, 0.01f);
  t.indptr.push_back(0);
  std::vector<uint32_t> col;
  for (int m = 0; m < t.columns; ++m) {
    col.clear();
    while (static_cast<int>(col.size()) < nnz) {
      col.push_back(pos(rng));
      if (static_cast<int>(col.size()) == nnz) {
        std::sort(col.begin(), col.end());
        col.erase(std::unique(col.begin(), col.end()), col.end());
      }
    }
    for (uint32_t p : col) {
      t.indices.push_back(p);
      t.values.push_back(value(rng));
    }
    t.indptr.push_back(static_cast<int64_t>(t.indices.size()));
    t.depth.push_back(static_cast<uint8_t>(depth(rng)));
  }
  return t;
}

SampleSet FullGrid(int n) {
  SampleSet s;
  s.width = s.height = n;
  for (int i = 0; i < n * n; ++i) {
    s.grid.push_back(i);
    s.position.push_back({});
    s.normal.push_back({0, 0, 1});
    s.albedo.push_back({0.8f, 0.7f, 0.6f});
  }
  return s;
}

// One grid size at a time (the dense 256² matrix is 1.6 GB).
struct Fixture {
  int n = 0;
  CompressedColumns columns;
  SampleSet samples;
  std::unique_ptr<Relighter> relighter;
  DenseTransport dense;
  double dense_seconds = 0;  // one dense frame, thread CPU time (best of 3)
  LightingCoefficients lighting;
};

Fixture& GetFixture(int n) {
  static Fixture f;
  if (f.n == n) return f;
  f = Fixture{};
  f.n = n;
  f.columns = SyntheticColumns(n, 1);
  f.samples = FullGrid(n);
  f.relighter = std::make_unique<Relighter>(*Relighter::Create(f.columns, f.samples));
  f.dense = Densify(f.columns);
  auto env = LoadEnvMap(WB_SHARED_DATA "/probes/grace.hdr");
  f.lighting = *LightingFromEnv(*env, kLightRes, WaveletFilter::kHaar);
  std::vector<float> out(3 * f.samples.cells());
  const std::vector<float> albedo = CellAlbedo(f.samples);
  f.dense_seconds = 1e30;
  for (int r = 0; r < 3; ++r) {
    const double t0 = ThreadSeconds();
    DenseRelight(f.dense, f.lighting.rgb, albedo, out);
    benchmark::DoNotOptimize(out.data());
    f.dense_seconds = std::min(f.dense_seconds, ThreadSeconds() - t0);
  }
  return f;
}

void BM_Relight(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), terms = static_cast<int>(state.range(1));
  Fixture& f = GetFixture(n);
  const WaveletLights lights = *SelectWaveletLights(f.lighting, terms);
  std::vector<float> out(3 * f.samples.cells());
  f.relighter->Relight(lights, out);  // grow the scratch outside the timing
  double total = 0;
  for (auto _ : state) {
    const double t0 = ThreadSeconds();
    f.relighter->Relight(lights, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
    total += ThreadSeconds() - t0;
  }
  int64_t nnz = 0;
  for (const WaveletLight& l : lights.lights) {
    nnz += f.columns.indptr[l.column + 1] - f.columns.indptr[l.column];
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["x_dense"] = f.dense_seconds / (total / static_cast<double>(state.iterations()));
  state.counters["nnz_per_col"] = static_cast<double>(f.columns.indices.size()) / f.columns.columns;
  state.counters["coeffs_per_frame"] = static_cast<double>(nnz);
}

void BM_Dense(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Fixture& f = GetFixture(n);
  std::vector<float> out(3 * f.samples.cells());
  const std::vector<float> albedo = CellAlbedo(f.samples);
  for (auto _ : state) {
    DenseRelight(f.dense, f.lighting.rgb, albedo, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Per-frame lighting for a rotating environment: ResampleToCubemap (all
// cores) + row transform + top-n selection, reported apart from Eq. 8.
void BM_Lighting(benchmark::State& state) {
  auto env = LoadEnvMap(WB_SHARED_DATA "/probes/grace.hdr");
  const std::vector<float> support = SupportSolidAngles(kLightRes);
  for (auto _ : state) {
    auto l = LightingFromEnv(*env, kLightRes, WaveletFilter::kHaar);
    auto lights = SelectWaveletLights(*l, 256, support);
    benchmark::DoNotOptimize(lights->lights.data());
  }
}

BENCHMARK(BM_Relight)->ArgsProduct({{128}, {64, 256, 1024}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dense)->Arg(128)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_Relight)->ArgsProduct({{256}, {64, 256, 1024}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dense)->Arg(256)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Lighting)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
