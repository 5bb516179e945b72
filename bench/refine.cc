// Visibility refinement row by row (core/transport/refined_row.h) against brute force
// (core/transport/transport_row.h) on the same samples, one thread, in the same run:
// rays per row, time per row, traced rays/s, and the error refinement costs
// per row. Scenes: builtin:cubes-wall (camera layout), the bunny and spot
// (hilbert layout); light resolutions 32, 64 and 128; 128 samples spread
// evenly over the layout.
//
//   build/bench_refine --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// Counters of BM_Refined:
//   x_rays     refined rays / brute-force rays over the same samples
//   x_time     refined time per row / brute force's (BM_Brute of the same case, run first)
//   err_rows   ‖refined − brute‖ / ‖brute‖ over the rows (all of it)
//   err_class  ‖refined − exact(brute)‖ / ‖brute‖: brute force's own rays valued the way
//              refinement values a traced texel, so what is left is what refinement
//              misclassified (err_rows − err_class is brute force's quadrature noise,
//              which the exact integral removes)
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "core/directions/texel_irradiance.h"
#include "core/transport/refined_row.h"
#include "core/transport/transport_row.h"
#include "worker/tiles/bake_context.h"

namespace wavebake {
namespace {

[[noreturn]] void Die(const std::string& what) {
  std::fprintf(stderr, "bench_refine: %s\n", what.c_str());
  std::exit(1);
}

struct SceneCase {
  const char* name;
  std::string spec, layout;
};

const SceneCase kScenes[] = {
    {"cubes-wall", "builtin:cubes-wall", "camera:64x64"},
    {"bunny", std::string(WB_SHARED_DATA) + "/models/bunny.obj", "hilbert:64x64"},
    {"spot", std::string(WB_SHARED_DATA) + "/models/spot.obj", "hilbert:64x64"},
};

constexpr int kSamples = 128;

struct Case {
  std::unique_ptr<BakeContext> ctx;
  std::vector<int32_t> ids;
  std::vector<std::vector<float>> brute;  // filled by BM_Brute
  double brute_seconds_per_row = 0;
  uint64_t brute_rays = 0;
};

Case& GetCase(int scene, int light_res) {
  static std::map<std::pair<int, int>, Case> cases;
  Case& c = cases[{scene, light_res}];
  if (c.ctx) return c;
  BakeParams p;
  p.light_res = light_res;
  p.layout = kScenes[scene].layout;
  absl::StatusOr<std::unique_ptr<BakeContext>> made = MakeBakeContext(kScenes[scene].spec, p);
  if (!made.ok()) Die(made.status().ToString());
  c.ctx = *std::move(made);
  const size_t s = c.ctx->samples.size();
  for (int i = 0; i < kSamples; ++i) c.ids.push_back(static_cast<int32_t>(i * s / kSamples));
  return c;
}

// A traced texel's value from brute force's rays (core/transport/refined_row.h): the
// exact integral of its part above the horizon times the cosine-weighted
// visible fraction of its rays there.
std::vector<float> ExactFromBrute(const BakeContext& ctx, const std::vector<float>& brute, Vec3 n) {
  std::vector<float> out = brute;
  const JitterPattern& p = ctx.jitter;
  for (int m = 0; m < ctx.cubemap.size(); ++m) {
    if (brute[m] == 0) continue;
    double sum_c = 0;
    for (int k = 0; k < p.per_texel; ++k) sum_c += std::max(0.0f, Dot(n, p.Direction(m, k)));
    const double all_visible = p.solid_angle[m] * sum_c / (p.per_texel * std::numbers::pi);
    out[m] = static_cast<float>(ClippedTexelIrradiance(ctx.cubemap, m, n) * brute[m] / all_visible);
  }
  return out;
}

void SetLabel(benchmark::State& state, int scene, int light_res) {
  state.SetLabel(std::string(kScenes[scene].name) + " N=" + std::to_string(light_res));
}

void BM_Brute(benchmark::State& state) {
  const int scene = state.range(0), light_res = state.range(1);
  Case& c = GetCase(scene, light_res);
  const BakeContext& ctx = *c.ctx;
  std::vector<float> row(ctx.cubemap.size());
  TransportStats stats;
  double seconds = 0;
  for (auto _ : state) {
    stats = {};
    c.brute.clear();
    const auto start = std::chrono::steady_clock::now();
    for (int32_t id : c.ids) {
      TransportRow(ctx.caster, ctx.cubemap, ctx.jitter, ctx.samples.position[id],
                   ctx.samples.normal[id], ctx.epsilon, row, &stats);
      c.brute.push_back(row);
    }
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  c.brute_seconds_per_row = seconds / state.iterations() / c.ids.size();
  c.brute_rays = stats.rays_traced;
  state.counters["rays/row"] = double(stats.rays_traced) / c.ids.size();
  state.counters["traced/s"] = benchmark::Counter(double(stats.rays_traced) * state.iterations(),
                                                  benchmark::Counter::kIsRate);
  SetLabel(state, scene, light_res);
}

void BM_Refined(benchmark::State& state) {
  const int scene = state.range(0), light_res = state.range(1);
  Case& c = GetCase(scene, light_res);
  const BakeContext& ctx = *c.ctx;
  std::vector<std::vector<float>> rows(c.ids.size(), std::vector<float>(ctx.cubemap.size()));
  RefineScratch scratch;
  TransportStats stats;
  double seconds = 0;
  for (auto _ : state) {
    stats = {};
    const auto start = std::chrono::steady_clock::now();
    for (size_t i = 0; i < c.ids.size(); ++i) {
      const int32_t id = c.ids[i];
      RefinedTransportRow(ctx.caster, ctx.cubemap, ctx.jitter, *ctx.refine,
                          ctx.samples.position[id], ctx.samples.normal[id], ctx.epsilon, rows[i],
                          &stats, scratch);
    }
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  state.counters["rays/row"] = double(stats.rays_traced) / c.ids.size();
  state.counters["traced/s"] = benchmark::Counter(double(stats.rays_traced) * state.iterations(),
                                                  benchmark::Counter::kIsRate);
  SetLabel(state, scene, light_res);
  if (c.brute.size() != c.ids.size()) return;  // BM_Brute of this case did not run
  double diff = 0, diff_class = 0, energy = 0;
  for (size_t i = 0; i < c.ids.size(); ++i) {
    const Vec3 n = ctx.samples.normal[c.ids[i]];
    const std::vector<float> exact = ExactFromBrute(ctx, c.brute[i], n);
    for (size_t m = 0; m < exact.size(); ++m) {
      const double b = c.brute[i][m], r = rows[i][m];
      diff += (r - b) * (r - b);
      diff_class += (r - exact[m]) * (r - exact[m]);
      energy += b * b;
    }
  }
  state.counters["x_rays"] = double(stats.rays_traced) / c.brute_rays;
  state.counters["x_time"] = seconds / state.iterations() / c.ids.size() / c.brute_seconds_per_row;
  state.counters["err_rows"] = std::sqrt(diff / energy);
  state.counters["err_class"] = std::sqrt(diff_class / energy);
}

}  // namespace

void RegisterAll() {
  for (int scene = 0; scene < 3; ++scene) {
    for (int n : {32, 64, 128}) {
      benchmark::RegisterBenchmark("BM_Brute", BM_Brute)
          ->Args({scene, n})
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
      benchmark::RegisterBenchmark("BM_Refined", BM_Refined)
          ->Args({scene, n})
          ->Unit(benchmark::kMillisecond);
    }
  }
}

}  // namespace wavebake

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  wavebake::RegisterAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
