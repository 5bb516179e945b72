// The Monte-Carlo reference (runtime/reference/reference.h) against closed forms and
// against a brute-force uniform-sphere estimate that shares none of its
// sampling code.
#include "runtime/reference/reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <numbers>
#include <numeric>
#include <random>

#include "core/products/brdf.h"
#include "core/transport/ray_caster.h"
#include "runtime/env/env_map.h"
#include "runtime/env/latlong.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake {
namespace {

// A 2×2 square at height y facing +Y (nothing above it).
Scene Floor(float y, float half = 1) {
  Mesh m;
  m.name = "floor";
  m.positions = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}};
  m.normals.assign(4, {0, 1, 0});
  m.triangles = {{0, 2, 1}, {0, 3, 2}};
  return Scene{.name = "floor", .meshes = {m}, .camera = {}};
}

// One sample per cell of a `count`×1 grid.
SampleSet ReceiverSamples(const std::vector<Vec3>& positions, const std::vector<Vec3>& normals) {
  SampleSet s;
  s.width = static_cast<int>(positions.size());
  s.height = 1;
  for (size_t i = 0; i < positions.size(); ++i) {
    s.grid.push_back(static_cast<int32_t>(i));
    s.position.push_back(positions[i]);
    s.normal.push_back(Normalize(normals[i]));
    s.albedo.push_back({1, 1, 1});
  }
  return s;
}

Vec3 Tilted(double degrees) {
  const double a = degrees * std::numbers::pi / 180;
  return {static_cast<float>(std::sin(a)), static_cast<float>(std::cos(a)), 0};
}

// White furnace of the reference: an unoccluded point under L ≡ 1 receives
// exactly 1, whatever its normal (the full hemisphere is visible).
TEST(Reference, UnoccludedPlaneUnderConstantIsOne) {
  auto caster = RayCaster::Build(Floor(0));
  ASSERT_TRUE(caster.ok());
  auto env = LoadEnvMap("builtin:constant");
  ASSERT_TRUE(env.ok());
  std::vector<Vec3> pos, nrm;
  for (int i = 0; i < 8; ++i) {
    pos.push_back({-0.8f + 0.2f * i, 0, 0.1f * i - 0.4f});
    nrm.push_back({0, 1, 0});
  }
  const SampleSet s = ReceiverSamples(pos, nrm);
  auto ref = ComputeReference(*caster, s, *env);
  ASSERT_TRUE(ref.ok()) << ref.status();
  EXPECT_TRUE(ref->converged);
  EXPECT_LE(ref->rel_se, 0.002);
  for (size_t i = 0; i < ref->rgb.size(); ++i) {
    EXPECT_NEAR(ref->rgb[i], 1.0, 4 * ref->standard_error[i] + 1e-6) << i;
  }
  std::printf("constant: rel_se %.5f, %lld rays for %d samples\n", ref->rel_se,
              static_cast<long long>(ref->rays), s.size());
}

// A sky that is 1 above the horizon and 0 below (rows of a 64×32 map split
// exactly at θ = π/2): an unoccluded receiver tilted by β from +Y gets the
// sky-view factor (1 + cos β)/2. Checks orientation (+Y is up in the map),
// the cosine, the 1/π and the tilted-normal sampling at once.
TEST(Reference, TiltedReceiverUnderUpperHemisphereSky) {
  auto caster = RayCaster::Build(Floor(-100, 0.01f));  // geometry far away, tiny
  ASSERT_TRUE(caster.ok());
  EnvMap sky{64, 32, std::vector<float>(64 * 32 * 3, 0.0f)};
  std::fill(sky.rgb.begin(), sky.rgb.begin() + 64 * 16 * 3, 1.0f);
  const std::vector<double> tilts = {0, 30, 60, 90, 120, 150, 180};
  std::vector<Vec3> pos, nrm;
  for (double t : tilts) {
    pos.push_back({0, 0, 0});
    nrm.push_back(Tilted(t));
  }
  auto ref = ComputeReference(*caster, ReceiverSamples(pos, nrm), sky);
  ASSERT_TRUE(ref.ok()) << ref.status();
  for (size_t i = 0; i < tilts.size(); ++i) {
    const double expect = (1 + std::cos(tilts[i] * std::numbers::pi / 180)) / 2;
    EXPECT_NEAR(ref->rgb[3 * i], expect, 4 * ref->standard_error[3 * i] + 1e-6) << tilts[i];
  }
  EXPECT_EQ(ref->rgb[3 * 6], 0.0f);  // facing down: no light above its horizon, no rays
}

// ∫ f_r(n, wo, ω) max(0, n·ω) · [ω.y > 0 or whole sphere] dω by the midpoint
// rule on a polar grid around the mirror direction: the glossy closed form
// of the two sky tests below, from Brdf::Eval alone.
double GlossyIntegral(const Brdf& brdf, Vec3 n, Vec3 wo, bool upper_sky_only) {
  const Vec3 axis = Normalize(n * (2 * Dot(n, wo)) - wo);
  Vec3 t, b;
  OrthonormalFrame(axis, t, b);
  const int nt = 1500, np = 360;
  double sum = 0;
  for (int i = 0; i < nt; ++i) {
    const double th = (i + 0.5) * std::numbers::pi / nt;
    for (int j = 0; j < np; ++j) {
      const double ph = (j + 0.5) * 2 * std::numbers::pi / np;
      const Vec3 w = Normalize(t * float(std::sin(th) * std::cos(ph)) +
                               b * float(std::sin(th) * std::sin(ph)) + axis * float(std::cos(th)));
      if (upper_sky_only && !(w.y > 0)) continue;
      sum += brdf.Eval(n, wo, w) * std::max(0.0f, Dot(n, w)) * std::sin(th);
    }
  }
  return sum * (std::numbers::pi / nt) * (2 * std::numbers::pi / np);
}

// Glossy white furnace: unoccluded under L ≡ 1 the reference is the BRDF's
// directional albedo; under the upper-hemisphere sky, tilted, the part of
// the lobe above the sky's horizon. The second needs the environment and
// BRDF densities of the mixture to agree with what each sampler draws.
TEST(Reference, GlossyReceiversSeeTheirLobe) {
  auto caster = RayCaster::Build(Floor(-100, 0.01f));
  ASSERT_TRUE(caster.ok());
  auto constant = LoadEnvMap("builtin:constant");
  ASSERT_TRUE(constant.ok());
  EnvMap sky{64, 32, std::vector<float>(64 * 32 * 3, 0.0f)};
  std::fill(sky.rgb.begin(), sky.rgb.begin() + 64 * 16 * 3, 1.0f);
  for (const char* spec : {"phong:32", "blinn:64", "ggx:0.3"}) {
    auto brdf = ParseBrdf(spec);
    ASSERT_TRUE(brdf.ok());
    std::vector<Vec3> pos, nrm, views;
    for (double tilt : {0.0, 40.0, 75.0}) {
      pos.push_back({0, 0, 0});
      nrm.push_back(Tilted(tilt));
      views.push_back(Normalize(Vec3{-0.3f, 0.8f, 0.4f}));
    }
    const SampleSet s = ReceiverSamples(pos, nrm);
    for (const EnvMap* env : {&*constant, &sky}) {
      ReferenceOptions o;
      o.brdf = brdf->get();
      o.views = views;
      auto ref = ComputeReference(*caster, s, *env, o);
      ASSERT_TRUE(ref.ok()) << ref.status();
      for (int i = 0; i < s.size(); ++i) {
        const double expect = GlossyIntegral(**brdf, s.normal[i], views[i], env == &sky);
        EXPECT_NEAR(ref->rgb[3 * i], expect, 4 * ref->standard_error[3 * i] + 2e-3 * expect)
            << spec << " receiver " << i << (env == &sky ? " sky" : " constant");
      }
    }
  }
}

// Brute force: every pixel of the map, `per_pixel` directions uniform in
// solid angle inside it (cos θ and φ uniform: stratified uniform sampling
// of the whole sphere), radiance of that pixel, visibility by
// RayCaster::Occluded one ray at a time. Shares no code with EnvSampler.
struct BruteForce {
  double mean[3] = {0, 0, 0}, se[3] = {0, 0, 0};
  int64_t rays = 0;
};
BruteForce StratifiedUniform(const RayCaster& caster, const EnvMap& env, Vec3 p, Vec3 n,
                             int per_pixel, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 origin = p + n * caster.DefaultEpsilon();
  BruteForce b;
  double var[3] = {0, 0, 0};
  for (int y = 0; y < env.height; ++y) {
    const double omega = LatLongPixelSolidAngle(y, env.width, env.height);
    for (int x = 0; x < env.width; ++x) {
      // Mean and variance of V·max(0, n·ω)/π over the pixel's strata.
      double sum = 0, sq = 0;
      for (int k = 0; k < per_pixel; ++k) {
        const double c0 = std::cos(std::numbers::pi * y / env.height),
                     c1 = std::cos(std::numbers::pi * (y + 1) / env.height);
        const double v = std::acos(c0 - u(rng) * (c0 - c1)) / std::numbers::pi;
        const Vec3 d = LatLongToDirection({(x + u(rng)) / env.width, v});
        const double c = Dot(n, d);
        if (c <= 0) continue;
        ++b.rays;
        if (caster.Occluded(origin, d, 0, 1e30f)) continue;
        sum += c / std::numbers::pi;
        sq += (c / std::numbers::pi) * (c / std::numbers::pi);
      }
      const double mean = sum / per_pixel;
      const double var_mean = std::max(0.0, sq / per_pixel - mean * mean) / (per_pixel - 1);
      const Vec3 l = env.Pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        b.mean[c] += l[c] * omega * mean;
        var[c] += std::pow(l[c] * omega, 2) * var_mean;
      }
    }
  }
  for (int c = 0; c < 3; ++c) b.se[c] = std::sqrt(var[c]);
  return b;
}

// Under grace.hdr (tiny, very bright sources) over the disk-over-plane scene:
// receivers in the disk's shadow, in the open, above the disk and sideways
// agree with the brute-force estimate within 4 combined standard errors.
// (Plain uniform sampling of the sphere is useless here: 2^20 rays leave
// 5–9 % standard error on the open receivers.)
TEST(Reference, GraceAgreesWithBruteForceUniformSampling) {
  auto scene = LoadScene("builtin:disk-over-plane");
  ASSERT_TRUE(scene.ok());
  auto caster = RayCaster::Build(*scene);
  ASSERT_TRUE(caster.ok());
  auto env = LoadEnvMap(WB_SHARED_DATA "/probes/grace.hdr");
  ASSERT_TRUE(env.ok()) << env.status();
  const std::vector<Vec3> pos = {{0, 0, 0}, {1.2f, 0, 0.3f}, {0, 0.76f, 0}, {0.3f, 0.2f, 0.1f}};
  const std::vector<Vec3> nrm = {{0, 1, 0}, {0, 1, 0}, Tilted(45), {1, 0.2f, -0.5f}};
  const SampleSet s = ReceiverSamples(pos, nrm);
  auto ref = ComputeReference(*caster, s, *env);
  ASSERT_TRUE(ref.ok()) << ref.status();
  std::printf("grace: rel_se %.5f, %lld rays, %.2f s\n", ref->rel_se,
              static_cast<long long>(ref->rays), ref->seconds);
  EXPECT_LE(ref->rel_se, 0.002);
  for (int i = 0; i < s.size(); ++i) {
    const BruteForce u = StratifiedUniform(*caster, *env, pos[i], s.normal[i], 8, 17 + i);
    for (int c = 0; c < 3; ++c) {
      const double r = ref->rgb[3 * i + c], se = ref->standard_error[3 * i + c];
      std::printf(
          "  receiver %d ch %d: reference %.5f ± %.5f  brute force %.5f ± %.5f (%lld rays)\n", i, c,
          r, se, u.mean[c], u.se[c], static_cast<long long>(u.rays));
      EXPECT_NEAR(r, u.mean[c], 4 * std::hypot(se, u.se[c])) << i << " " << c;
      EXPECT_LT(u.se[c], 0.01 * u.mean[c]);  // the brute force is itself informative
    }
  }
}

TEST(Reference, BitIdenticalForAnyThreadCount) {
  auto scene = LoadScene("builtin:disk-over-plane");
  ASSERT_TRUE(scene.ok());
  auto caster = RayCaster::Build(*scene);
  ASSERT_TRUE(caster.ok());
  auto env = LoadEnvMap("builtin:sky");
  ASSERT_TRUE(env.ok());
  std::vector<Vec3> pos, nrm;
  for (int i = 0; i < 8; ++i) {
    pos.push_back({0.1f * i, 0, 0});
    nrm.push_back({0, 1, 0});
  }
  const SampleSet s = ReceiverSamples(pos, nrm);
  ReferenceOptions o;
  o.target_rel_se = 0.01;
  o.threads = 1;
  auto one = ComputeReference(*caster, s, *env, o);
  o.threads = 2;
  auto two = ComputeReference(*caster, s, *env, o);
  ASSERT_TRUE(one.ok() && two.ok());
  EXPECT_EQ(one->rgb, two->rgb);
  EXPECT_EQ(one->rays, two->rays);
}

// Progress (what `eval` shows while it traces): each sample reported once
// per pass, from whichever thread traced it, ending at done == total.
TEST(Reference, ProgressReportsEverySampleOncePerPass) {
  auto caster = RayCaster::Build(Floor(0));
  ASSERT_TRUE(caster.ok());
  auto env = LoadEnvMap("builtin:sky");
  ASSERT_TRUE(env.ok());
  std::vector<Vec3> pos, nrm;
  for (int i = 0; i < 6; ++i) {
    pos.push_back({0.1f * i, 0, 0});
    nrm.push_back({0, 1, 0});
  }
  const SampleSet s = ReceiverSamples(pos, nrm);
  std::mutex mu;
  std::vector<int64_t> seen;
  ReferenceOptions o;
  o.target_rel_se = 0.05;
  o.threads = 3;
  o.progress = [&](int64_t done, int64_t total) {
    std::lock_guard lock(mu);
    EXPECT_EQ(total, 2 * 6);
    seen.push_back(done);
  };
  ASSERT_TRUE(ComputeReference(*caster, s, *env, o).ok());
  std::sort(seen.begin(), seen.end());
  std::vector<int64_t> expected(12);
  std::iota(expected.begin(), expected.end(), 1);
  EXPECT_EQ(seen, expected);
}

TEST(Reference, RejectsBadInput) {
  auto caster = RayCaster::Build(Floor(0));
  ASSERT_TRUE(caster.ok());
  const SampleSet s = ReceiverSamples({{0, 0, 0}}, {{0, 1, 0}});
  EnvMap square{16, 16, std::vector<float>(16 * 16 * 3, 1.0f)};
  auto r = ComputeReference(*caster, s, square);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("env"), std::string_view::npos);
  ReferenceOptions o;
  o.target_rel_se = 0;
  r = ComputeReference(*caster, s, *LoadEnvMap("builtin:constant"), o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("target_rel_se"), std::string_view::npos);
}

}  // namespace
}  // namespace wavebake
