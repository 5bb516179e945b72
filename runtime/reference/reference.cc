#include "runtime/reference/reference.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <thread>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/util/parallel_for.h"
#include "runtime/env/env_sampler.h"
#include "runtime/reference/batch_means.h"
#include "runtime/reference/stream_rng.h"

namespace wavebake {
namespace {

constexpr int kBatch = 128;     // draws per Embree call, per stratified batch, per check
constexpr int kMinBatches = 8;  // fewer batch means give no usable standard error
constexpr uint64_t kReferenceDomain = 0x7265662d72617973ull;  // "ref-rays"

class Rng : public StreamRng {
 public:
  Rng(uint64_t seed, uint64_t stream) : StreamRng(seed, kReferenceDomain, stream) {}
};

// One sample's estimate by batch means: each batch of kBatch draws, stratified
// in the first uniform, is an unbiased estimate of B; batches are independent,
// so their spread gives the standard error (stratified draws inside a batch
// are not independent, so the per-draw variance would overstate it).
struct Estimate : BatchMeans {
  int64_t traced = 0;
  int64_t rays() const { return batches * kBatch; }
};

struct Receiver {
  Vec3 origin, normal;
};

// A batch's traced directions and what each adds if unoccluded; TraceInto
// adds the batch's mean (over all kBatch draws, the untraced ones being 0) to
// the estimate.
struct RayBatch {
  alignas(64) float x[kBatch], y[kBatch], z[kBatch];
  std::array<double, 3> f[kBatch];
  uint8_t occluded[kBatch];
  int count = 0;

  void Add(Vec3 w, std::array<double, 3> value) {
    x[count] = w.x, y[count] = w.y, z[count] = w.z;
    f[count++] = value;
  }
  void TraceInto(const RayCaster& caster, Vec3 origin, Estimate& e) {
    const size_t n = static_cast<size_t>(count);
    caster.OccludedFan(origin, {{x, n}, {y, n}, {z, n}}, 0, std::numeric_limits<float>::infinity(),
                       {occluded, n});
    std::array<double, 3> batch{};
    for (int i = 0; i < count; ++i) {
      if (occluded[i]) continue;
      for (int c = 0; c < 3; ++c) batch[c] += f[i][c];
    }
    e.Add(batch, kBatch);
    e.traced += count;
  }
};

// One batch of kBatch draws for one receiver: draw i takes its block-curve
// uniform from the stratum [i, i+1)/kBatch (jittered), the rest at random.
void TraceBatch(const RayCaster& caster, const EnvSampler& sampler, std::span<const double> cdf,
                const Receiver& r, Rng& rng, Estimate& e) {
  RayBatch b;
  for (int i = 0; i < kBatch; ++i) {
    std::array<double, 5> u;
    for (double& v : u) v = rng.Next01();
    u[0] = (i + u[0]) / kBatch;
    const EnvSampler::Draw d = sampler.Sample(cdf, u);
    const double cosine = Dot(r.normal, d.direction);
    if (!(cosine > 0)) continue;  // f = 0: counted, not traced
    b.Add(d.direction,
          {d.weight[0] * cosine / std::numbers::pi, d.weight[1] * cosine / std::numbers::pi,
           d.weight[2] * cosine / std::numbers::pi});
  }
  b.TraceInto(caster, r.origin, e);
}

// One batch for a glossy receiver: even draws from the environment, odd
// ones from the BRDF's lobe, each weighted by the balance heuristic.
void TraceGlossyBatch(const RayCaster& caster, const EnvSampler& sampler,
                      std::span<const double> cdf, const Receiver& r, Vec3 view, const Brdf& brdf,
                      Rng& rng, Estimate& e) {
  RayBatch b;
  constexpr int kHalf = kBatch / 2;
  for (int i = 0; i < kBatch; ++i) {
    std::array<double, 5> u;
    for (double& v : u) v = rng.Next01();
    const double stratum = (i / 2 + u[0]) / kHalf;
    Vec3 w;
    Vec3 radiance;
    double p_env, p_brdf;
    if (i % 2 == 0) {
      u[0] = stratum;
      const EnvSampler::Draw d = sampler.Sample(cdf, u);
      w = d.direction;
      p_env = d.pdf;
      radiance = sampler.Radiance(w);
      p_brdf = brdf.Pdf(r.normal, view, w);
    } else {
      w = brdf.Sample(r.normal, view, stratum, u[1]);
      p_brdf = brdf.Pdf(r.normal, view, w);
      p_env = sampler.Pdf(cdf, w);
      radiance = sampler.Radiance(w);
    }
    const double cosine = Dot(r.normal, w);
    if (!(cosine > 0)) continue;
    const double fr = brdf.Eval(r.normal, view, w);
    const double p_mix = 0.5 * (p_env + p_brdf);
    if (!(fr > 0) || !(p_mix > 0)) continue;
    b.Add(w, {radiance[0] * fr * cosine / p_mix, radiance[1] * fr * cosine / p_mix,
              radiance[2] * fr * cosine / p_mix});
  }
  b.TraceInto(caster, r.origin, e);
}

absl::Status CheckInputs(const SampleSet& s, const EnvMap& env, const ReferenceOptions& o) {
  if (env.height <= 0 || env.width != 2 * env.height ||
      env.rgb.size() != static_cast<size_t>(env.width) * env.height * 3) {
    return absl::InvalidArgumentError(absl::StrCat("env: ", env.width, "x", env.height,
                                                   " is not a lat-long map (width = 2 height)"));
  }
  if (s.grid.size() != static_cast<size_t>(s.cells()) || s.normal.size() != s.position.size() ||
      s.albedo.size() != s.position.size()) {
    return absl::InvalidArgumentError("samples: grid, normal or albedo sizes disagree");
  }
  if (o.brdf && o.brdf->ViewDependent() && o.views.size() != s.position.size()) {
    return absl::InvalidArgumentError(absl::StrCat("views: ", o.views.size(),
                                                   " view directions for ", s.position.size(),
                                                   " samples (", o.brdf->Name(), ")"));
  }
  if (!(o.target_rel_se > 0) || o.min_rays < 2 || o.max_rays < o.min_rays) {
    return absl::InvalidArgumentError(absl::StrCat(
        "reference options: target_rel_se ", o.target_rel_se, ", min_rays ", o.min_rays,
        ", max_rays ", o.max_rays, " (need target > 0 and 2 ≤ min ≤ max)"));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<ReferenceResult> ComputeReference(const RayCaster& caster, const SampleSet& samples,
                                                 const EnvMap& env, const ReferenceOptions& o) {
  if (absl::Status s = CheckInputs(samples, env, o); !s.ok()) return s;
  const auto start = std::chrono::steady_clock::now();
  const EnvSampler sampler(env);
  const float eps = o.epsilon > 0 ? o.epsilon : caster.DefaultEpsilon();
  const int threads = o.threads > 0
                          ? o.threads
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int count = samples.size();
  const bool glossy = o.brdf != nullptr && o.brdf->ViewDependent();
  std::vector<Estimate> est(count);
  std::vector<double> cdf_total(count);
  std::vector<Rng> rng;  // one stream per sample, continued by pass 2
  rng.reserve(count);
  for (int s = 0; s < count; ++s) rng.emplace_back(o.seed, static_cast<uint64_t>(s));

  // Both passes rebuild the receiver's block distribution (2 K entries)
  // rather than keep one per sample.
  auto receiver = [&](int s) {
    return Receiver{samples.position[s] + samples.normal[s] * eps, samples.normal[s]};
  };
  auto run = [&](int s, const auto& keep_going) {
    std::vector<double> cdf(sampler.blocks() + 1);
    if (glossy) {
      const Vec3 n = samples.normal[s], wo = o.views[s];
      cdf_total[s] =
          sampler.ReceiverCdf([&](Vec3 c, float r) { return o.brdf->CapBound(n, wo, c, r); }, cdf);
    } else {
      cdf_total[s] = sampler.ReceiverCdf(samples.normal[s], cdf);
    }
    if (cdf_total[s] == 0) return;  // no light above the horizon: B = 0 exactly
    const Receiver rec = receiver(s);
    if (glossy) {
      while (keep_going(est[s]))
        TraceGlossyBatch(caster, sampler, cdf, rec, o.views[s], *o.brdf, rng[s], est[s]);
    } else {
      while (keep_going(est[s])) TraceBatch(caster, sampler, cdf, rec, rng[s], est[s]);
    }
  };
  std::atomic<int64_t> visited{0};
  auto visited_one = [&] {
    const int64_t done = ++visited;
    if (o.progress) o.progress(done, 2 * int64_t{count});
  };
  // Pass 1, the pilot: min_rays for everyone (whole batches, at least 8).
  ParallelForWorkers(count, threads, 1, [&](int, int s) {
    run(s, [&](const Estimate& e) { return e.rays() < o.min_rays || e.batches < kMinBatches; });
    visited_one();
  });
  double sum_sq = 0;
  int64_t terms = 0;
  for (int s = 0; s < count; ++s) {
    const Vec3 a = samples.albedo[s];
    for (int c = 0; c < 3; ++c) sum_sq += std::pow(est[s].Mean(c) * a[c], 2);
    terms += 3;
  }
  const double rms = terms ? std::sqrt(sum_sq / terms) : 0;
  const double target = o.target_rel_se * rms;
  // Pass 2: each sample until SE_c · albedo_c ≤ target · R, or max_rays.
  ParallelForWorkers(count, threads, 1, [&](int, int s) {
    const Vec3 a = samples.albedo[s];
    run(s, [&](const Estimate& e) {
      if (e.rays() >= o.max_rays) return false;
      for (int c = 0; c < 3; ++c) {
        if (e.StdErr(c) * a[c] > target) return true;
      }
      return false;
    });
    visited_one();
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
    const Estimate& e = est[s];
    for (int c = 0; c < 3; ++c) {
      const double b = e.Mean(c) * a[c];
      const double se = cdf_total[s] == 0 ? 0.0 : e.StdErr(c) * a[c];
      r.rgb[3 * cell + c] = static_cast<float>(b);
      r.standard_error[3 * cell + c] = static_cast<float>(se);
      se_sq += se * se;
      b_sq += b * b;
    }
    r.rays += e.traced;
    if (cdf_total[s] > 0 && e.rays() >= o.max_rays) r.converged = false;
  }
  r.rel_se = b_sq > 0 ? std::sqrt(se_sq / b_sq) : 0;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace wavebake
