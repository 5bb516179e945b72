// Near-field relighting frame rate (runtime/near_field/near_field.h) at 128×128
// samples on one core, with the paper's truncation (1 % source, 30 % target
// terms, Sun & Ramamoorthi Fig. 11), beside the brute force of the same
// frame — per sample, the light resampled onto the face in pixels and a
// dense dot product with the pixel-basis row (runtime/near_field/near_field_brute.h) —
// measured in the same run. `x_brute` is the brute-force frame time over
// this benchmark's frame time (thread CPU time, so other load on the
// machine counts less); `x_separable` the same against a stronger baseline
// that resamples separably along the face's axes (BruteResample). Couplings: computed from the
// canonical coefficients (Eq. 16) or looked up in the memory-based table (§5.3.2).
//
// The store: builtin:cubes-wall, camera:128x128, plane:4, N = 32, target
// 1 %, baked once into build/bench_tmp/near_cubes.wbk (seconds to minutes)
// or taken from $WB_NEAR_STORE. The light: docs/lights/softbox.json (four
// flat panels: 4 source terms), and an 8×8 checker of its colours, each
// drawn into a source image of R = 32 (the paper's wavelet order), 64 or
// 128: the brute force's resampling grows with R², the wavelet path with
// the source terms kept.
//   ./build/bench_near_field --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include "runtime/near_field/near_field.h"

#include <benchmark/benchmark.h>
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include "driver/bake/embedded_bake.h"
#include "runtime/near_field/area_light.h"
#include "runtime/near_field/near_field_brute.h"

namespace wavebake {
namespace {

double ThreadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// An 8×8 checker of the softbox's four colours: finer detail, more source
// terms (the paper's Fig. 10 lights range from flat to busy).
EnvMap Checker8() {
  const float c[4][3] = {
      {1, 0.84f, 0.58f}, {1, 0.4f, 0.05f}, {0.1f, 0.58f, 0.64f}, {0.58f, 0.3f, 1}};
  EnvMap t{32, 32, std::vector<float>(32 * 32 * 3)};
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int ch = 0; ch < 3; ++ch)
        t.rgb[(y * 32 + x) * 3 + ch] = c[(x / 4 + 2 * (y / 4)) % 4][ch];
  return t;
}

struct Fixture {
  NearFieldStore store;
  AreaLight softbox;
  std::unique_ptr<BruteForceNearField> brute;
  std::optional<CouplingTable> table;
};

// The brute-force frames of one light, measured once per light.
struct Baseline {
  double per_texel_seconds = 0, separable_seconds = 0;
  std::vector<float> rgb;
};

std::filesystem::path StorePath() {
  if (const char* env = std::getenv("WB_NEAR_STORE")) return env;
  const std::filesystem::path p =
      std::filesystem::path(WB_SOURCE_DIR) / "build/bench_tmp" / "near_cubes.wbk";
  if (std::filesystem::exists(p / ".zattrs")) return p;
  std::filesystem::create_directories(p.parent_path());
  BakeParams params;
  params.light_res = 32;
  params.layout = "camera:128x128";
  params.light_domain = *ParseLightDomain("plane:4");
  std::fprintf(stderr, "baking %s (once)...\n", p.c_str());
  absl::StatusOr<v1::Job> job = driver::EmbeddedBake("builtin:cubes-wall", params, p, {});
  if (!job.ok() || job->phase() != v1::PHASE_DONE) {
    std::fprintf(stderr, "bake failed: %s\n",
                 job.ok() ? job->error().c_str() : std::string(job.status().message()).c_str());
    std::exit(1);
  }
  return p;
}

[[noreturn]] void Die(const absl::Status& s) {
  std::fprintf(stderr, "bench_near_field: %s\n", std::string(s.message()).c_str());
  std::exit(1);
}

Fixture& Shared() {
  static Fixture* f = [] {
    absl::StatusOr<NearFieldStore> store = OpenNearFieldStore(StorePath());
    if (!store.ok()) Die(store.status());
    absl::StatusOr<std::vector<AreaLight>> lights =
        LoadAreaLights(std::filesystem::path(WB_SOURCE_DIR) / "docs/lights/softbox.json");
    if (!lights.ok()) Die(lights.status());
    auto* fx = new Fixture{*std::move(store), lights->front(), nullptr, std::nullopt};
    fx->brute = std::make_unique<BruteForceNearField>(fx->store);
    absl::StatusOr<CouplingTable> table =
        CouplingTable::Build({.source_res = fx->softbox.resolution,
                              .target_res = fx->store.face.n(),
                              .s_min = 0.5,
                              .s_max = 8,
                              .scales = 64,
                              .offsets = 256});
    if (!table.ok()) Die(table.status());
    fx->table = *std::move(table);
    std::fprintf(stderr, "coupling table: %.1f MB, built in %.2f s\n", fx->table->bytes() / 1e6,
                 fx->table->build_seconds());
    return fx;
  }();
  return *f;
}

// docs/lights/softbox.json at source resolution r, its own texture or the checker.
AreaLight LightOf(const Fixture& f, int r, bool checker) {
  AreaLight l = f.softbox;
  l.resolution = r;
  if (checker) l.texture = Checker8();
  return l;
}

const Baseline& BaselineOf(const AreaLight& light) {
  static std::map<std::pair<int, bool>, Baseline> cache;
  const auto key =
      std::pair{light.resolution,
                light.texture.rgb.size() > 0 && light.texture.rgb != Shared().softbox.texture.rgb};
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  Fixture& f = Shared();
  Baseline b;
  const std::vector<LightCanvas> canvases = {DrawLight(light)};
  b.rgb.resize(3 * f.store.samples.cells());
  // The fastest of 3 frames: the least disturbed by the machine's other load.
  for (BruteResample mode : {BruteResample::kPerTexel, BruteResample::kSeparable}) {
    double best = 1e30;
    for (int i = 0; i < 3; ++i) {
      const double t0 = ThreadSeconds();
      f.brute->Relight(canvases, 1, b.rgb, mode);
      best = std::min(best, ThreadSeconds() - t0);
    }
    (mode == BruteResample::kPerTexel ? b.per_texel_seconds : b.separable_seconds) = best;
  }
  return cache.emplace(key, std::move(b)).first->second;
}

// Relative RMS of a against b over the unmasked cells.
double RelRms(const std::vector<float>& a, const std::vector<float>& b) {
  double e = 0, n = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(b[i])) continue;
    e += (a[i] - b[i]) * (a[i] - b[i]);
    n += double(b[i]) * b[i];
  }
  return std::sqrt(e / n);
}

// Args: source %, target %, source resolution R, texture (0 softbox, 1 checker).
void NearField(benchmark::State& state, bool table) {
  Fixture& f = Shared();
  const AreaLight light = LightOf(f, static_cast<int>(state.range(2)), state.range(3) == 1);
  const Baseline& base = BaselineOf(light);
  NearFieldOptions o{.source_fraction = state.range(0) / 100.0,
                     .target_fraction = state.range(1) / 100.0,
                     .table = table ? &*f.table : nullptr,
                     .threads = 1};
  std::vector<float> rgb(3 * f.store.samples.cells());
  double seconds = 0;
  int64_t frames = 0;
  NearFieldStats stats;
  for (auto _ : state) {
    const double t0 = ThreadSeconds();
    absl::StatusOr<NearFieldStats> s = RelightNearField(f.store, {&light, 1}, o, rgb);
    const double dt = ThreadSeconds() - t0;
    if (!s.ok()) Die(s.status());
    stats = *s;
    state.SetIterationTime(dt);
    seconds += dt;
    ++frames;
  }
  const double frame = seconds / std::max<int64_t>(frames, 1);
  state.counters["fps"] = 1 / frame;
  state.counters["brute_fps"] = 1 / base.per_texel_seconds;
  state.counters["x_brute"] = base.per_texel_seconds / frame;
  state.counters["x_separable"] = base.separable_seconds / frame;
  state.counters["targets"] = double(stats.targets) / std::max<int64_t>(1, stats.lit_samples);
  state.counters["sources"] = double(stats.sources);
  state.counters["err_vs_brute"] = RelRms(rgb, base.rgb);
}

void BM_NearFieldComputed(benchmark::State& s) { NearField(s, false); }
void BM_NearFieldTable(benchmark::State& s) { NearField(s, true); }

// The operating point (1 % / 30 %) for the softbox and the checker at three
// source resolutions; then the paper's Fig. 11 fractions for the softbox.
BENCHMARK(BM_NearFieldComputed)
    ->ArgsProduct({{1}, {30}, {32, 64, 128}, {0, 1}})
    ->Args({1, 1, 32, 0})
    ->Args({1, 20, 32, 0})
    ->Args({5, 40, 32, 0})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NearFieldTable)->Args({1, 30, 32, 0})->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
