// Throughput of the bake's hot loop, TransportRow (core/transport/transport_row.h), on
// a tessellated sphere over a tessellated plane (~6k triangles), N=32, K=4,
// one thread — beside, measured in the same run, a baseline (the row's M·K
// directions traced one by one with rtcOccluded1 and no horizon culling) and
// the raw Embree kernels of RayCaster::OccludedFan on exactly the rays a row
// traces, in texel order and in Z order.
//
//   build/bench_transport --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// items_per_second counts the row's M·K directions, so TransportRow /
// Baseline is the speed-up per row that batching and culling buy; "traced/s"
// counts the rays really handed to Embree; TransportRow's x_fastest_kernel is
// its traced/s over the fastest kernel's (target ≥ 0.85: the row loop adds
// little to what Embree itself costs), and BM_TransportRowPaired measures the
// same ratio pairwise, row by row, which the machine's load does not move.
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/transport/ray_caster.h"
#include "core/transport/transport_row.h"

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

double ThreadCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// The fastest BM_Fan's traced rays per CPU second so far (BM_TransportRow's yardstick).
double fastest_fan_rate = 0;

// Texel m's position in the order rays are handed over: index order, or Z
// order within each face (2×2 texel blocks, then 4×4, ...).
int ZOrderKey(const Cubemap& c, int m) {
  const Texel t = c.TexelOf(m);
  int z = 0;
  for (int b = 0; b < 8; ++b) z |= ((t.x >> b) & 1) << (2 * b) | ((t.y >> b) & 1) << (2 * b + 1);
  return t.face << 16 | z;
}

struct Fan {
  Vec3 origin;
  std::vector<float> x, y, z;
};

// The rays a row really traces, per sample (its upper hemisphere, in texel
// order, or with z_order in Z order).
std::vector<Fan> RowFans(const Fixture& f, bool z_order) {
  std::vector<int> texels(f.cubemap.size());
  for (int m = 0; m < f.cubemap.size(); ++m) texels[m] = m;
  if (z_order)
    std::sort(texels.begin(), texels.end(),
              [&](int a, int b) { return ZOrderKey(f.cubemap, a) < ZOrderKey(f.cubemap, b); });
  const float eps = f.caster->DefaultEpsilon();
  std::vector<Fan> fans;
  for (const Sample& s : f.samples) {
    Fan fan{s.position + s.normal * eps, {}, {}, {}};
    for (int m : texels) {
      for (int k = 0; k < f.pattern.per_texel; ++k) {
        const Vec3 d = f.pattern.Direction(m, k);
        if (Dot(d, s.normal) <= 0) continue;
        fan.x.push_back(d.x), fan.y.push_back(d.y), fan.z.push_back(d.z);
      }
    }
    fans.push_back(std::move(fan));
  }
  return fans;
}

// What each RayCaster::OccludedFan kernel does with the rays a row really
// traces; this is how RayCaster::kDefaultFanKernel was chosen.
void BM_Fan(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const auto kernel = static_cast<FanKernel>(state.range(0));
  const std::vector<Fan> fans = RowFans(f, state.range(1) != 0);
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<uint8_t> occluded(f.rays_per_row());
  size_t i = 0, rays = 0;
  const double cpu_start = ThreadCpuSeconds();
  for (auto _ : state) {
    const Fan& fan = fans[i++ % fans.size()];
    f.caster->OccludedFan(fan.origin, {fan.x, fan.y, fan.z}, 0, inf, occluded, kernel);
    benchmark::DoNotOptimize(occluded.data());
    rays += fan.x.size();
  }
  fastest_fan_rate = std::max(fastest_fan_rate, rays / (ThreadCpuSeconds() - cpu_start));
  state.counters["traced/s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Fan)
    ->ArgNames({"kernel", "z_order"})  // kernel 0 single, 1 packet8, 2 packet16, 3 stream
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// After BM_Fan: its fastest rate is the row's yardstick.
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
  // Against the fastest raw kernel of this run (target ≥ 0.85), traced rays
  // per CPU second of both.
  if (fastest_fan_rate > 0) {
    state.counters["x_fastest_kernel"] = benchmark::Counter(
        static_cast<double>(stats.rays_traced) / fastest_fan_rate, benchmark::Counter::kIsRate);
  }
}
BENCHMARK(BM_TransportRow)->Unit(benchmark::kMillisecond);

// The row loop's own cost: the same rows against a scene every ray misses
// at the root of the BVH (one small triangle far away), so that what is
// left is building the batches, culling, and adding up the cosines.
void BM_TransportRowNothingToHit(benchmark::State& state) {
  const Fixture& f = GetFixture();
  Mesh far;
  far.name = "far";
  far.positions = {{100, 100, 100}, {100.1f, 100, 100}, {100, 100.1f, 100}};
  far.triangles = {{0, 1, 2}};
  Scene scene;
  scene.meshes = {far};
  const absl::StatusOr<RayCaster> caster = RayCaster::Build(scene);
  if (!caster.ok()) std::exit(1);
  std::vector<float> row(f.cubemap.size());
  TransportStats stats;
  size_t i = 0;
  for (auto _ : state) {
    const Sample& s = f.samples[i++ % f.samples.size()];
    TransportRow(*caster, f.cubemap, f.pattern, s.position, s.normal, 1e-4f, row, &stats);
    benchmark::DoNotOptimize(row.data());
  }
  state.counters["ns/ray"] =
      benchmark::Counter(static_cast<double>(stats.rays_traced),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TransportRowNothingToHit)->Unit(benchmark::kMicrosecond);

// The row loop's yardstick measured pairwise: each iteration traces one
// sample's row with TransportRow and exactly its rays with the raw packet16
// and stream kernels (Z order, the fastest in BM_Fan), in all six orders in
// turn, timing each call with the thread's CPU clock. Whatever the machine
// does meanwhile slows all three alike, where the ratio of two separate
// benchmarks drifts by ±0.05 from run to run. x_fastest_kernel_paired = the
// faster kernel's CPU time over TransportRow's, for the same rays (target
// ≥ 0.85).
void BM_TransportRowPaired(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const std::vector<Fan> fans = RowFans(f, /*z_order=*/true);
  const float eps = f.caster->DefaultEpsilon(), inf = std::numeric_limits<float>::infinity();
  std::vector<float> row(f.cubemap.size());
  std::vector<uint8_t> occluded(f.rays_per_row());
  double row_cpu = 0, packet_cpu = 0, stream_cpu = 0;
  size_t i = 0;
  for (auto _ : state) {
    const size_t at = i++ % f.samples.size();
    const Sample& s = f.samples[at];
    const Fan& fan = fans[at];
    auto run_row = [&] {
      TransportRow(*f.caster, f.cubemap, f.pattern, s.position, s.normal, eps, row, nullptr);
    };
    auto run_packet = [&] {
      f.caster->OccludedFan(fan.origin, {fan.x, fan.y, fan.z}, 0, inf, occluded,
                            FanKernel::kPacket16);
    };
    auto run_stream = [&] {
      f.caster->OccludedFan(fan.origin, {fan.x, fan.y, fan.z}, 0, inf, occluded,
                            FanKernel::kStream);
    };
    std::pair<std::function<void()>, double*> calls[] = {
        {run_row, &row_cpu}, {run_packet, &packet_cpu}, {run_stream, &stream_cpu}};
    // All six orders in turn, so that each call comes first (meeting the
    // cache the previous sample's calls left), and right after each of the
    // others (over the same rays), equally often: rotations alone would
    // always put the packet kernel after the row and never the row after it.
    const size_t order = (i / f.samples.size()) % 6;
    if (order >= 3) std::swap(calls[1], calls[2]);
    std::rotate(std::begin(calls), std::begin(calls) + order % 3, std::end(calls));
    for (auto& [call, total] : calls) {
      const double t0 = ThreadCpuSeconds();
      call();
      *total += ThreadCpuSeconds() - t0;
    }
    benchmark::DoNotOptimize(row.data());
    benchmark::DoNotOptimize(occluded.data());
  }
  state.counters["x_packet16"] = packet_cpu / row_cpu;
  state.counters["x_stream"] = stream_cpu / row_cpu;
  state.counters["x_fastest_kernel_paired"] = std::min(packet_cpu, stream_cpu) / row_cpu;
}
BENCHMARK(BM_TransportRowPaired)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
