// SelectForBudget / CountForBudget (core/columns/nla.h) on column-sized inputs, beside
// a full sort of the same magnitudes (what the halving quickselect avoids).
//   ./build/bench_nla --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "core/columns/nla.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace wavebake {
namespace {

// Wavelet-like column: most energy in few coefficients, a long small tail.
std::vector<float> Column(int n) {
  std::mt19937 rng(7);
  std::normal_distribution<float> g(0, 1);
  std::vector<float> v(n);
  for (int i = 0; i < n; ++i) v[i] = g(rng) / (1 + 0.01f * i);
  return v;
}

double Budget(const std::vector<float>& v) {
  double total = 0;
  for (float x : v) total += double(x) * x;
  return 1e-4 * total;  // the default 1 % target error, squared
}

void BM_SelectForBudget(benchmark::State& state) {
  const std::vector<float> v = Column(static_cast<int>(state.range(0)));
  const double budget = Budget(v);
  for (auto _ : state) benchmark::DoNotOptimize(SelectForBudget(v, {}, budget));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_CountForBudget(benchmark::State& state) {
  const std::vector<float> v = Column(static_cast<int>(state.range(0)));
  const double budget = Budget(v);
  for (auto _ : state) benchmark::DoNotOptimize(CountForBudget(v, {}, budget));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_FullSortBaseline(benchmark::State& state) {
  const std::vector<float> v = Column(static_cast<int>(state.range(0)));
  std::vector<float> mags(v.size());
  for (auto _ : state) {
    for (size_t i = 0; i < v.size(); ++i) mags[i] = std::fabs(v[i]);
    std::sort(mags.begin(), mags.end());
    benchmark::DoNotOptimize(mags.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(BM_SelectForBudget)->Arg(4096)->Arg(65536);
BENCHMARK(BM_CountForBudget)->Arg(4096)->Arg(65536);
BENCHMARK(BM_FullSortBaseline)->Arg(4096)->Arg(65536);

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
