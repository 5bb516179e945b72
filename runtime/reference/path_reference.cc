#include "runtime/reference/path_reference.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "runtime/env/env_sampler.h"
#include "runtime/reference/batch_means.h"
#include "runtime/reference/path_scene.h"

namespace wavebake {
namespace {

constexpr int kPathBatch = 64;      // paths per batch mean
constexpr int kMinPathBatches = 8;  // fewer batch means give no usable standard error

// PCG32 (O'Neill 2014, XSH RR): the path tracer's own stream, one per
// sample, apart from every other random number of the project.
class PathRng {
 public:
  PathRng(uint64_t seed, uint64_t sample) : inc_((sample << 1u) | 1u) {
    Next();
    state_ += seed ^ 0x70617468747263ull;  // "pathtrc"
    Next();
  }
  double Next01() {  // [0, 1) from 53 bits of two outputs
    const uint64_t hi = Next(), lo = Next();
    return static_cast<double>(((hi << 32) | lo) >> 11) * 0x1p-53;
  }

 private:
  uint32_t Next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
  }
  uint64_t state_ = 0, inc_;
};

// A cosine-distributed direction around unit n: the disk point (√u, 2πv)
// lifted to the hemisphere, in a frame from Gram–Schmidt against the axis
// least aligned with n.
Vec3 CosineSample(Vec3 n, double u, double v) {
  const Vec3 axis = std::fabs(n.x) < 0.6f   ? Vec3{1, 0, 0}
                    : std::fabs(n.y) < 0.6f ? Vec3{0, 1, 0}
                                            : Vec3{0, 0, 1};
  const Vec3 t = Normalize(axis - n * Dot(axis, n));
  const Vec3 b = Cross(n, t);
  const double r = std::sqrt(u), phi = 2 * std::numbers::pi * v;
  const double z = std::sqrt(std::max(0.0, 1 - u));
  return Normalize(t * static_cast<float>(r * std::cos(phi)) +
                   b * static_cast<float>(r * std::sin(phi)) + n * static_cast<float>(z));
}

struct PathEstimate : BatchMeans {
  int64_t rays = 0;
  int64_t paths() const { return batches * kPathBatch; }
};

struct PathSetup {
  const Scene& scene;
  const PathScene& tracer;
  const EnvSampler& sampler;
  std::span<const double> free_cdf;  // the map's own distribution (bound 1)
  std::vector<double> mean_albedo;   // ρ̄ per mesh
  int bounces = 0;
  float epsilon = 0;
};

// Next-event estimate at (origin, normal): L(ω)·max(0, n·ω)/π / pdf(ω), 0 if occluded.
std::array<double, 3> NextEvent(const PathSetup& p, std::span<const double> cdf, Vec3 origin,
                                Vec3 normal, const std::array<double, 5>& u, int64_t& rays) {
  const EnvSampler::Draw d = p.sampler.Sample(cdf, u);
  const double cosine = Dot(normal, d.direction);
  if (!(cosine > 0)) return {};
  ++rays;
  if (p.tracer.Blocked(origin, d.direction)) return {};
  const double k = cosine / std::numbers::pi;
  return {d.weight[0] * k, d.weight[1] * k, d.weight[2] * k};
}

void TracePathBatch(const PathSetup& p, std::span<const double> receiver_cdf, Vec3 position,
                    Vec3 normal, PathRng& rng, PathEstimate& e) {
  std::array<double, 3> batch{};
  for (int i = 0; i < kPathBatch; ++i) {
    Vec3 n = normal;
    Vec3 origin = position + n * p.epsilon;
    double throughput = 1;
    for (int depth = 0;; ++depth) {
      std::array<double, 5> u;
      for (double& v : u) v = rng.Next01();
      if (depth == 0) u[0] = (i + u[0]) / kPathBatch;  // stratified over the batch
      const std::span<const double> cdf = depth == 0 ? receiver_cdf : p.free_cdf;
      if (cdf.back() > 0) {
        const std::array<double, 3> l = NextEvent(p, cdf, origin, n, u, e.rays);
        for (int c = 0; c < 3; ++c) batch[c] += throughput * l[c];
      }
      if (depth == p.bounces) break;
      const Vec3 dir = CosineSample(n, rng.Next01(), rng.Next01());
      ++e.rays;
      const std::optional<PathHit> hit = p.tracer.Trace(origin, dir);
      if (!hit || !hit->front) break;  // escaped (counted by NEE), or a back face
      throughput *= p.mean_albedo[hit->mesh];
      if (!(throughput > 0)) break;
      n = hit->normal;
      origin = hit->position + n * p.epsilon;
    }
  }
  e.Add(batch, kPathBatch);
}

// fn(0..count−1) on `threads` threads, samples handed out one by one (each
// has its own stream, so the result does not depend on who runs it).
template <typename Fn>
void PathParallel(int count, int threads, const Fn& fn) {
  std::atomic<int> next{0};
  auto loop = [&] {
    for (int s = next++; s < count; s = next++) fn(s);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(loop);
  loop();
  for (std::thread& t : pool) t.join();
}

}  // namespace

absl::StatusOr<ReferenceResult> ComputePathReference(const Scene& scene, const SampleSet& samples,
                                                     const EnvMap& env,
                                                     const PathReferenceOptions& o) {
  if (env.height <= 0 || env.width != 2 * env.height ||
      env.rgb.size() != static_cast<size_t>(env.width) * env.height * 3)
    return absl::InvalidArgumentError(absl::StrCat("env: ", env.width, "x", env.height,
                                                   " is not a lat-long map (width = 2 height)"));
  if (o.bounces < 0)
    return absl::InvalidArgumentError(absl::StrCat("bounces: ", o.bounces, " is negative"));
  if (!(o.target_rel_se > 0) || o.min_paths < 2 || o.max_paths < o.min_paths)
    return absl::InvalidArgumentError(absl::StrCat(
        "reference options: target_rel_se ", o.target_rel_se, ", min_paths ", o.min_paths,
        ", max_paths ", o.max_paths, " (need target > 0 and 2 ≤ min ≤ max)"));
  if (samples.normal.size() != samples.position.size() ||
      samples.albedo.size() != samples.position.size())
    return absl::InvalidArgumentError("samples: position, normal or albedo sizes disagree");

  const auto start = std::chrono::steady_clock::now();
  const EnvSampler sampler(env);
  std::vector<double> free_cdf(sampler.blocks() + 1);
  sampler.ReceiverCdf([](Vec3, float) { return 1.0; }, free_cdf);
  std::vector<double> mean_albedo;
  for (const Mesh& m : scene.meshes)
    mean_albedo.push_back((double(m.albedo.x) + m.albedo.y + m.albedo.z) / 3);
  absl::StatusOr<PathScene> tracer = PathScene::Build(scene);
  if (!tracer.ok()) return tracer.status();
  const PathSetup setup{.scene = scene,
                        .tracer = *tracer,
                        .sampler = sampler,
                        .free_cdf = free_cdf,
                        .mean_albedo = std::move(mean_albedo),
                        .bounces = o.bounces,
                        .epsilon = o.epsilon > 0 ? o.epsilon : tracer->Offset()};
  const int threads = o.threads > 0
                          ? o.threads
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));

  const int count = samples.size();
  std::vector<PathEstimate> est(count);
  std::vector<PathRng> rng;
  rng.reserve(count);
  for (int s = 0; s < count; ++s) rng.emplace_back(o.seed, static_cast<uint64_t>(s));
  std::atomic<int64_t> visits{0};
  auto run = [&](int s, const auto& keep_going) {
    std::vector<double> cdf(sampler.blocks() + 1);
    sampler.ReceiverCdf(samples.normal[s], cdf);
    // No light above x's horizon: the first vertex's estimate is 0, but
    // bounced light may still arrive, so the paths run all the same.
    while (keep_going(est[s]))
      TracePathBatch(setup, cdf, samples.position[s], samples.normal[s], rng[s], est[s]);
    const int64_t done = visits.fetch_add(1, std::memory_order_relaxed) + 1;
    if (o.progress) o.progress(done, 2 * int64_t{count});
  };
  PathParallel(count, threads, [&](int s) {
    run(s, [&](const PathEstimate& e) {
      return e.paths() < o.min_paths || e.batches < kMinPathBatches;
    });
  });
  double sum_sq = 0;
  for (int s = 0; s < count; ++s)
    for (int c = 0; c < 3; ++c) sum_sq += std::pow(est[s].Mean(c) * samples.albedo[s][c], 2);
  const double target = o.target_rel_se * (count ? std::sqrt(sum_sq / (3.0 * count)) : 0.0);
  PathParallel(count, threads, [&](int s) {
    const Vec3 a = samples.albedo[s];
    run(s, [&](const PathEstimate& e) {
      if (e.paths() >= o.max_paths) return false;
      for (int c = 0; c < 3; ++c)
        if (e.StdErr(c) * a[c] > target) return true;
      return false;
    });
  });

  ReferenceResult r;
  const size_t cells = static_cast<size_t>(samples.cells());
  r.rgb.assign(3 * cells, std::numeric_limits<float>::quiet_NaN());
  r.standard_error.assign(3 * cells, std::numeric_limits<float>::quiet_NaN());
  double se_sq = 0, b_sq = 0;
  for (size_t cell = 0; cell < cells; ++cell) {
    const int32_t s = samples.grid[cell];
    if (s < 0) continue;
    const Vec3 a = samples.albedo[s];
    for (int c = 0; c < 3; ++c) {
      const double b = est[s].Mean(c) * a[c];
      const double se = est[s].StdErr(c) * a[c];
      r.rgb[3 * cell + c] = static_cast<float>(b);
      r.standard_error[3 * cell + c] = static_cast<float>(se);
      se_sq += se * se;
      b_sq += b * b;
    }
    r.rays += est[s].rays;
    if (est[s].paths() >= o.max_paths) r.converged = false;
  }
  r.rel_se = b_sq > 0 ? std::sqrt(se_sq / b_sq) : 0;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace wavebake
