// Throughput of the bake's hot loop, TransportRow (core/transport_row.h), on
// a tessellated sphere over a tessellated plane (~6k triangles), N=32, K=4,
// one thread — beside a baseline measured in the same run: the row's M·K
// directions traced one by one with rtcOccluded1 and no horizon culling.
//
//   build/bench_transport --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// items_per_second counts the row's M·K directions in every benchmark, so the
// ratio TransportRow / Baseline is the speed-up per row that batching and
// culling buy; "traced/s" counts the rays really handed to Embree.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "core/cubemap.h"
#include "core/jitter_pattern.h"
#include "core/ray_caster.h"
#include "core/transport_row.h"

namespace wavebake {
namespace {

constexpr int kLightRes = 32, kSupersample = 4;

Mesh Sphere(Vec3 centre, float radius, int slices, int stacks) {
  Mesh m;
  m.name = "sphere";
  for (int j = 0; j <= stacks; ++j) {
    const double theta = std::numbers::pi * j / stacks;
    for (int i = 0; i < slices; ++i) {
      const double phi = 2 * std::numbers::pi * i / slices;
      const Vec3 n{static_cast<float>(std::sin(theta) * std::cos(phi)),
                   static_cast<float>(std::sin(theta) * std::sin(phi)),
                   static_cast<float>(std::cos(theta))};
      m.positions.push_back(centre + n * radius);
      m.normals.push_back(n);
    }
  }
  auto id = [&](int i, int j) { return static_cast<uint32_t>(j * slices + i % slices); };
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      m.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  }
  return m;
}

Mesh Grid(float half, int cells) {
  Mesh m;
  m.name = "plane";
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      m.positions.push_back({-half + 2 * half * i / cells, -half + 2 * half * j / cells, 0});
      m.normals.push_back({0, 0, 1});
    }
  }
  auto id = [&](int i, int j) { return static_cast<uint32_t>(j * (cells + 1) + i); };
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

struct Sample {
  Vec3 position, normal;
};

// Everything a row needs, built once: the scene's caster, the cubemap, the
// shared jitter pattern, and 64 samples on the plane (in and out of the
// sphere's shadow) and on the sphere (its underside faces the plane).
struct Fixture {
  Cubemap cubemap{kLightRes};
  JitterPattern pattern;
  std::optional<RayCaster> caster;
  std::vector<Sample> samples;
  size_t triangles = 0;

  Fixture() {
    Scene scene;
    scene.meshes = {Grid(4, 32), Sphere({0, 0, 1.2f}, 1, 64, 24)};
    for (const Mesh& m : scene.meshes) triangles += m.triangles.size();
    auto built = RayCaster::Build(scene);
    auto made = MakeJitterPattern(cubemap, kSupersample, 1);
    if (!built.ok() || !made.ok()) {
      std::fprintf(stderr, "bench_transport: setup failed\n");
      std::exit(1);
    }
    caster.emplace(*std::move(built));
    pattern = *std::move(made);
    for (int i = 0; i < 32; ++i) {
      const float a = 2 * std::numbers::pi_v<float> * i / 32, r = 0.3f + 2.5f * (i % 4) / 4;
      samples.push_back({{r * std::cos(a), r * std::sin(a), 0}, {0, 0, 1}});
      const float theta = std::numbers::pi_v<float> * (i + 0.5f) / 32;
      const Vec3 n{std::sin(theta) * std::cos(3 * a), std::sin(theta) * std::sin(3 * a),
                   std::cos(theta)};
      samples.push_back({Vec3{0, 0, 1.2f} + n, n});
    }
  }
  int rays_per_row() const { return cubemap.size() * pattern.per_texel; }
};

const Fixture& GetFixture() {
  static const Fixture fixture;  // built once, shared by all benchmarks
  return fixture;
}

void BM_TransportRow(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const float eps = f.caster->DefaultEpsilon();
  std::vector<float> row(f.cubemap.size());
  TransportStats stats;
  size_t i = 0;
  for (auto _ : state) {
    const Sample& s = f.samples[i++ % f.samples.size()];
    TransportRow(*f.caster, f.cubemap, f.pattern, s.position, s.normal, eps, row, &stats);
    benchmark::DoNotOptimize(row.data());
  }
  state.SetItemsProcessed(state.iterations() * f.rays_per_row());
  state.counters["traced/s"] =
      benchmark::Counter(static_cast<double>(stats.rays_traced), benchmark::Counter::kIsRate);
  state.counters["triangles"] = static_cast<double>(f.triangles);
}
BENCHMARK(BM_TransportRow)->Unit(benchmark::kMillisecond);

// The baseline: every direction of the row, one rtcOccluded1 call each, no
// culling and no packets.
void BM_BaselineOccluded1(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const float eps = f.caster->DefaultEpsilon(), inf = std::numeric_limits<float>::infinity();
  size_t i = 0;
  for (auto _ : state) {
    const Sample& s = f.samples[i++ % f.samples.size()];
    const Vec3 origin = s.position + s.normal * eps;
    int blocked = 0;
    for (int r = 0; r < f.rays_per_row(); ++r) {
      blocked +=
          f.caster->Occluded(origin, {f.pattern.x[r], f.pattern.y[r], f.pattern.z[r]}, 0, inf);
    }
    benchmark::DoNotOptimize(blocked);
  }
  state.SetItemsProcessed(state.iterations() * f.rays_per_row());
  state.counters["traced/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * f.rays_per_row(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BaselineOccluded1)->Unit(benchmark::kMillisecond);

// What each RayCaster::OccludedFan kernel does with the rays a row really
// traces (the upper hemisphere of each sample, in texel order); this is how
// RayCaster::kDefaultFanKernel was chosen.
void BM_Fan(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const auto kernel = static_cast<FanKernel>(state.range(0));
  const float eps = f.caster->DefaultEpsilon(), inf = std::numeric_limits<float>::infinity();
  struct Fan {
    Vec3 origin;
    std::vector<float> x, y, z;
  };
  std::vector<Fan> fans;
  for (const Sample& s : f.samples) {
    Fan fan{s.position + s.normal * eps, {}, {}, {}};
    for (int r = 0; r < f.rays_per_row(); ++r) {
      const Vec3 d{f.pattern.x[r], f.pattern.y[r], f.pattern.z[r]};
      if (Dot(d, s.normal) <= 0) continue;
      fan.x.push_back(d.x), fan.y.push_back(d.y), fan.z.push_back(d.z);
    }
    fans.push_back(std::move(fan));
  }
  std::vector<uint8_t> occluded(f.rays_per_row());
  size_t i = 0, rays = 0;
  for (auto _ : state) {
    const Fan& fan = fans[i++ % fans.size()];
    f.caster->OccludedFan(fan.origin, {fan.x, fan.y, fan.z}, 0, inf, occluded, kernel);
    benchmark::DoNotOptimize(occluded.data());
    rays += fan.x.size();
  }
  state.counters["traced/s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Fan)
    ->ArgName("kernel")  // 0 single, 1 packet8, 2 packet16, 3 stream
    ->DenseRange(0, 3)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
