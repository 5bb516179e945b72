#include "core/transport/transport_row.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <thread>
#include <vector>

#include "tests/core/test_shapes.h"

namespace wavebake {
namespace {

using test_shapes::BuildOrDie;
using test_shapes::Disk;
using test_shapes::Quad;
using test_shapes::SceneOf;
using test_shapes::Tangents;

JitterPattern PatternOrDie(const Cubemap& cubemap, int supersample, uint64_t seed = 1) {
  absl::StatusOr<JitterPattern> p = MakeJitterPattern(cubemap, supersample, seed);
  EXPECT_TRUE(p.ok()) << p.status();
  return *std::move(p);
}

struct Bake {
  Cubemap cubemap;
  JitterPattern pattern;
  Bake(int n, int k, uint64_t seed = 1) : cubemap(n), pattern(PatternOrDie(cubemap, k, seed)) {}

  std::vector<float> Row(const RayCaster& caster, Vec3 x, Vec3 n, TransportStats* stats = nullptr,
                         float eps = -1) const {
    std::vector<float> row(cubemap.size(), -1.0f);
    TransportRow(caster, cubemap, pattern, x, n, eps < 0 ? caster.DefaultEpsilon() : eps, row,
                 stats);
    return row;
  }
};

double Sum(const std::vector<float>& row) { return std::accumulate(row.begin(), row.end(), 0.0); }

// White furnace (DESIGN.md §1): with nothing occluding and L ≡ 1,
// B = Σ_m T[s,m] = ∫ cos/π dω = 1, whatever the point and the normal.
//
// The row is a jittered quadrature, so its error is random with the seed:
// over 200 seeds its standard deviation is σ ≈ 0.18 % at N=8 K=4, 0.2 % at
// N=16 K=1, ≤ 0.05 % beyond (σ ∝ 1/(N²√K)) — 0.5 % is ≥ 2.5σ there. One
// jittered direction per 0.2-rad texel (N=8, K=1) has σ ≈ 0.75 %: that case
// gets a 3σ bound here and its mean over seeds is checked below.
double FurnaceTolerance(int res, int k) { return res == 8 && k == 1 ? 0.025 : 0.005; }

TEST(TransportRowTest, WhiteFurnaceIntegratesToOne) {
  const Vec3 normals[] = {{0, 0, 1}, Normalize({1, 2, 3}), Normalize({-0.3f, 0.9f, -0.2f})};
  for (Vec3 n : normals) {
    const Vec3 centre{0.2f, -0.1f, 0.4f};
    const RayCaster caster = BuildOrDie(SceneOf({Quad(centre, n, 5)}));
    const auto [u, v] = Tangents(n);
    const Vec3 points[] = {centre, centre + u * 3.1f - v * 0.7f, centre - u * 4.5f + v * 4.2f};
    for (int res : {8, 16, 32}) {
      for (int k : {1, 4}) {
        const Bake bake(res, k);
        for (Vec3 x : points) {
          TransportStats stats;
          const std::vector<float> row = bake.Row(caster, x, n, &stats);
          EXPECT_NEAR(Sum(row), 1, FurnaceTolerance(res, k))
              << "N=" << res << " K=" << k << " n=" << n.x << "," << n.y << "," << n.z;
          EXPECT_EQ(stats.rays_occluded, 0u);
          for (float t : row) ASSERT_GE(t, 0);
        }
      }
    }
  }
}

// The coarsest, unsupersampled row is right on average over job seeds: the
// mean of 32 rows (σ/√32 ≈ 0.13 %) is within 0.5 % of 1.
TEST(TransportRowTest, WhiteFurnaceCoarsestRowIsRightOnAverage) {
  const Vec3 normals[] = {{0, 0, 1}, Normalize({1, 2, 3})};
  for (Vec3 n : normals) {
    const RayCaster caster = BuildOrDie(SceneOf({Quad({0, 0, 0}, n, 5)}));
    double mean = 0;
    constexpr int kSeeds = 32;
    for (uint64_t seed = 1; seed <= kSeeds; ++seed) {
      mean += Sum(Bake(8, 1, seed).Row(caster, {0, 0, 0}, n)) / kSeeds;
    }
    EXPECT_NEAR(mean, 1, 0.005) << n.x << "," << n.y << "," << n.z;
  }
}

// An opaque disk of radius r at height h on the normal's axis subtends a cone
// of half-angle θ, sin²θ = r²/(r²+h²); the cosine-weighted fraction of a cone
// about the normal is sin²θ, so Σ_m T = 1 − r²/(r²+h²). The disk is a regular
// 512-gon inscribed in the circle: its r² is off by at most 1 − cos²(π/512)
// ≈ 4e-5 relative, far below the 1 % tolerance.
TEST(TransportRowTest, DiskOnTheAxisBlocksItsProjectedSolidAngle) {
  const Vec3 x{0.5f, -0.25f, 1};
  const Vec3 n = Normalize({0.2f, -0.1f, 1});
  for (float r_over_h : {0.5f, 1.0f, 2.0f}) {
    const float h = 1.5f, r = r_over_h * h;
    const RayCaster caster = BuildOrDie(SceneOf({Disk(x + n * h, -n, r, 512)}));
    const double expected = 1 - r * r / (r * r + h * h);
    for (int res : {32, 64}) {
      const Bake bake(res, 4);
      TransportStats stats;
      const double sum = Sum(bake.Row(caster, x, n, &stats));
      EXPECT_NEAR(sum, expected, 0.01 * expected) << "r/h=" << r_over_h << " N=" << res;
      EXPECT_GT(stats.rays_occluded, 0u);
    }
  }
}

// The row's index m and the cubemap's directions agree end to end: texels
// whose 4 corners are all inside the disk's cone are fully blocked (exactly
// 0), texels whose corners are all outside it are fully lit.
TEST(TransportRowTest, BlockedTexelsAreTheOnesBehindTheDisk) {
  const Vec3 x{0, 0, 0}, n{0, 0, 1};
  const float h = 1, r = 1;  // cone half-angle 45°
  const RayCaster caster = BuildOrDie(SceneOf({Disk(x + n * h, -n, r, 512)}));
  const Bake bake(16, 4);
  const std::vector<float> row = bake.Row(caster, x, n);
  const float cos_cone = h / std::sqrt(h * h + r * r);
  int inside = 0, outside = 0;
  for (int m = 0; m < bake.cubemap.size(); ++m) {
    const Texel t = bake.cubemap.TexelOf(m);
    const int n_edge = bake.cubemap.n();
    bool all_in = true, all_out_lit = true;
    for (auto [s, tt] : {std::pair{t.x, t.y}, {t.x + 1, t.y}, {t.x, t.y + 1}, {t.x + 1, t.y + 1}}) {
      const Vec3 c = Cubemap::FaceDirection(t.face, double(s) / n_edge, double(tt) / n_edge);
      all_in = all_in && c.z > cos_cone + 1e-3f;
      all_out_lit = all_out_lit && c.z < cos_cone - 1e-3f && c.z > 1e-3f;
    }
    if (all_in) {
      EXPECT_EQ(row[m], 0) << m;
      ++inside;
    }
    if (all_out_lit) {
      EXPECT_GT(row[m], 0) << m;
      ++outside;
    }
  }
  EXPECT_GT(inside, 50);
  EXPECT_GT(outside, 200);
}

// Texels entirely below the horizon are exactly 0 and cost no rays. A floor
// under the sample would occlude every downward ray, so "no ray was occluded"
// proves none was traced below the horizon.
TEST(TransportRowTest, TexelsBelowTheHorizonAreZeroAndUntraced) {
  const RayCaster caster = BuildOrDie(SceneOf({Quad({0, 0, -1}, {0, 0, 1}, 100)}));
  for (int res : {8, 32}) {
    const Bake bake(res, 4);
    TransportStats stats;
    const std::vector<float> row = bake.Row(caster, {0, 0, 0}, {0, 0, 1}, &stats);
    // Normal +z: all of −Z, none of +Z and half of each side face lie below.
    const uint64_t below = 3ull * res * res;
    EXPECT_EQ(stats.texels_culled, below);
    EXPECT_EQ(stats.rays_traced, (6ull * res * res - below) * 4);
    EXPECT_EQ(stats.rays_occluded, 0u);
    EXPECT_NEAR(Sum(row), 1, 0.005);
  }

  // A tilted normal: the culled texels are found here from the texel corners.
  const Vec3 n = Normalize({0.4f, -0.7f, 0.3f});
  const Bake bake(16, 4);
  TransportStats stats;
  const RayCaster tilted = BuildOrDie(SceneOf({Quad(n * -1.0f, n, 100)}));
  const std::vector<float> row = bake.Row(tilted, {0, 0, 0}, n, &stats);
  uint64_t below = 0;
  for (int m = 0; m < bake.cubemap.size(); ++m) {
    const Texel t = bake.cubemap.TexelOf(m);
    bool all_below = true;
    for (auto [s, tt] : {std::pair{t.x, t.y}, {t.x + 1, t.y}, {t.x, t.y + 1}, {t.x + 1, t.y + 1}}) {
      all_below = all_below && Dot(n, Cubemap::FaceDirection(t.face, s / 16.0, tt / 16.0)) <= 0;
    }
    if (!all_below) continue;
    ++below;
    EXPECT_EQ(row[m], 0.0f) << m;
  }
  EXPECT_EQ(stats.texels_culled, below);
  EXPECT_LE(stats.rays_traced, (6ull * 16 * 16 - below) * 4);
  EXPECT_EQ(stats.rays_occluded, 0u);
}

// DESIGN.md §1 "What a row holds": a visibility row is V alone. Nothing
// above the horizon occludes, and the floor that would block every downward
// ray is never asked: the row is exactly 1 everywhere.
TEST(VisibilityRowTest, UnoccludedIsOneEverywhereBelowTheHorizonIncluded) {
  const RayCaster caster = BuildOrDie(SceneOf({Quad({0, 0, -1}, {0, 0, 1}, 100)}));
  for (int res : {8, 16}) {
    const Bake bake(res, 4);
    std::vector<float> row(bake.cubemap.size(), -1.0f);
    TransportStats stats;
    VisibilityRow(caster, bake.cubemap, bake.pattern, {0, 0, 0}, {0, 0, 1}, caster.DefaultEpsilon(),
                  row, &stats);
    for (float v : row) ASSERT_EQ(v, 1.0f);
    EXPECT_EQ(stats.rays_occluded, 0u);
    EXPECT_EQ(stats.texels_culled, 3ull * res * res);
  }
}

// With one direction per texel the diffuse entry is exactly the visibility
// entry times Ω_m · max(0, n·ω_m)/π of that direction: the two transports
// trace the same rays.
TEST(VisibilityRowTest, TimesSolidAngleAndCosineIsTheDiffuseRow) {
  const Vec3 x{0, 0, 0}, n = Normalize({0.1f, 0.2f, 1});
  const RayCaster caster = BuildOrDie(SceneOf({Disk({0.2f, 0, 1}, {0, 0, -1}, 1.2f, 128)}));
  const Bake bake(16, 1);
  const std::vector<float> diffuse = bake.Row(caster, x, n);
  std::vector<float> v(bake.cubemap.size());
  VisibilityRow(caster, bake.cubemap, bake.pattern, x, n, caster.DefaultEpsilon(), v, nullptr);
  int blocked = 0;
  for (int m = 0; m < bake.cubemap.size(); ++m) {
    ASSERT_TRUE(v[m] == 0 || v[m] == 1) << m;
    const double c = std::max(0.0f, Dot(n, bake.pattern.Direction(m, 0)));
    EXPECT_NEAR(diffuse[m], bake.pattern.solid_angle[m] * v[m] * c / std::numbers::pi, 1e-7) << m;
    blocked += v[m] == 0;
  }
  EXPECT_GT(blocked, 100);
}

// A scene with real visibility edges for the determinism tests.
Scene DiskOverFloor() {
  return SceneOf({Quad({0, 0, 0}, {0, 0, 1}, 4), Disk({0.3f, 0, 1}, {0, 0, -1}, 0.8f, 64)});
}

std::vector<Vec3> FloorPoints() {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.push_back({-1.5f + 0.4f * i, 0.1f * i, 0});
  return points;
}

TEST(TransportRowTest, SameRowTwiceAndFromTwoThreadsIsBitIdentical) {
  const RayCaster caster = BuildOrDie(DiskOverFloor());
  const Bake bake(16, 4, 77);
  const std::vector<Vec3> points = FloorPoints();
  std::vector<std::vector<float>> serial;
  for (Vec3 p : points) serial.push_back(bake.Row(caster, p, {0, 0, 1}));
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(bake.Row(caster, points[i], {0, 0, 1}), serial[i]) << i;
  }
  std::vector<std::vector<float>> threaded[2];
  auto work = [&](int t) {
    for (int rep = 0; rep < 3; ++rep) {
      for (Vec3 p : points) threaded[t].push_back(bake.Row(caster, p, {0, 0, 1}));
    }
  };
  std::thread a(work, 0), b(work, 1);
  a.join();
  b.join();
  for (int t = 0; t < 2; ++t) {
    ASSERT_EQ(threaded[t].size(), 3 * points.size());
    for (size_t i = 0; i < threaded[t].size(); ++i) {
      EXPECT_EQ(threaded[t][i], serial[i % points.size()]) << "thread " << t << " row " << i;
    }
  }
}

// The jitter is the job seed's (changing it changes the row, not its
// integral), and it is shared by all samples: on an unoccluded plane two
// different points see bit-identical rows, which per-sample jitter would not.
TEST(TransportRowTest, JitterFollowsTheSeedAndIsSharedBySamples) {
  const RayCaster caster = BuildOrDie(DiskOverFloor());
  const Vec3 x{0.1f, 0.2f, 0};
  const std::vector<float> a = Bake(16, 4, 1).Row(caster, x, {0, 0, 1});
  const std::vector<float> b = Bake(16, 4, 2).Row(caster, x, {0, 0, 1});
  EXPECT_NE(a, b);
  EXPECT_NEAR(Sum(a), Sum(b), 0.01);

  const RayCaster plane = BuildOrDie(SceneOf({Quad({0, 0, 0}, {0, 0, 1}, 4)}));
  const Bake bake(16, 4, 5);
  EXPECT_EQ(bake.Row(plane, {-2.5f, 1.5f, 0}, {0, 0, 1}),
            bake.Row(plane, {3.0f, -0.5f, 0}, {0, 0, 1}));
}

// BruteForceRays counts exactly the rays TransportRow hands to Embree.
TEST(TransportRowTest, BruteForceRaysCountsTheTracedRays) {
  const RayCaster caster = BuildOrDie(DiskOverFloor());
  const Vec3 normals[] = {{0, 0, 1}, Normalize({1, 2, 3}), Normalize({-0.3f, 0.9f, -0.2f})};
  for (int res : {8, 16}) {
    const Bake bake(res, 4);
    for (Vec3 n : normals) {
      TransportStats stats;
      bake.Row(caster, {0, 0, 0.5f}, n, &stats);
      EXPECT_EQ(BruteForceRays(bake.cubemap, bake.pattern, n), stats.rays_traced);
    }
  }
}

TEST(TransportRowTest, StatsAddUpOverRows) {
  const RayCaster caster = BuildOrDie(DiskOverFloor());
  const Bake bake(8, 4);
  TransportStats one, both;
  bake.Row(caster, {0, 0, 0}, {0, 0, 1}, &one);
  bake.Row(caster, {0, 0, 0}, {0, 0, 1}, &both);
  bake.Row(caster, {0, 0, 0}, {0, 0, 1}, &both);
  EXPECT_GT(one.rays_traced, 0u);
  EXPECT_EQ(both.rays_traced, 2 * one.rays_traced);
  EXPECT_EQ(both.rays_occluded, 2 * one.rays_occluded);
  EXPECT_EQ(both.texels_culled, 2 * one.texels_culled);
}

}  // namespace
}  // namespace wavebake
