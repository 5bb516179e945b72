// Visibility refinement (core/transport/refined_row.h) against brute force
// (core/transport/transport_row.h) and against closed forms: the white furnace, a disk
// on the normal's axis, brute force's own rays valued the way refinement
// values a traced texel, and a thin wire that coarse probes miss unless the
// guards are on. Determinism as for brute force.
#include "core/transport/refined_row.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>
#include <thread>
#include <vector>

#include "core/directions/texel_irradiance.h"
#include "core/transport/transport_row.h"
#include "tests/core/test_shapes.h"

namespace wavebake {
// Named, so that its helpers stay apart from transport_row_test.cc's in a
// unity batch.
namespace refined_row_test {
namespace {

using test_shapes::BuildOrDie;
using test_shapes::Disk;
using test_shapes::Quad;
using test_shapes::SceneOf;

JitterPattern PatternOrDie(const Cubemap& cubemap, int k, uint64_t seed) {
  absl::StatusOr<JitterPattern> p = MakeJitterPattern(cubemap, k, seed);
  EXPECT_TRUE(p.ok()) << p.status();
  return *std::move(p);
}

struct Rows {
  Cubemap cubemap;
  JitterPattern pattern;
  RefinePlan plan;
  Rows(int n, int k = 4, RefineOptions options = {}, uint64_t seed = 1)
      : cubemap(n), pattern(PatternOrDie(cubemap, k, seed)), plan(cubemap, pattern, options) {}

  std::vector<float> Brute(const RayCaster& caster, Vec3 x, Vec3 n,
                           TransportStats* stats = nullptr) const {
    std::vector<float> row(cubemap.size());
    TransportRow(caster, cubemap, pattern, x, n, caster.DefaultEpsilon(), row, stats);
    return row;
  }
  std::vector<float> Refined(const RayCaster& caster, Vec3 x, Vec3 n,
                             TransportStats* stats = nullptr) const {
    RefineScratch scratch;
    return Refined(caster, x, n, stats, scratch);
  }
  std::vector<float> Refined(const RayCaster& caster, Vec3 x, Vec3 n, TransportStats* stats,
                             RefineScratch& scratch) const {
    std::vector<float> row(cubemap.size(), -1.0f);
    RefinedTransportRow(caster, cubemap, pattern, plan, x, n, caster.DefaultEpsilon(), row, stats,
                        scratch);
    return row;
  }

  // All four corners strictly above the horizon of n, in double.
  bool Above(int m, Vec3 n) const {
    const Texel t = cubemap.TexelOf(m);
    for (int c = 0; c < 4; ++c) {
      const auto p = Cubemap::FacePoint(t.face, double(t.x + c % 2) / cubemap.n(),
                                        double(t.y + c / 2) / cubemap.n());
      if (!(n.x * p[0] + n.y * p[1] + n.z * p[2] > 0)) return false;
    }
    return true;
  }

  // How many of texel m's K rays are above the horizon of n.
  int RaysAbove(int m, Vec3 n) const {
    int above = 0;
    for (int j = 0; j < pattern.per_texel; ++j) above += Dot(n, pattern.Direction(m, j)) > 0;
    return above;
  }

  // Brute force's rays valued as refinement values a traced texel: the
  // exact integral of its part above the horizon times the cosine-weighted
  // visible fraction of its rays there (brute force's value over its value
  // with every such ray visible). What refinement gives if it classifies
  // every texel right.
  std::vector<float> ExactFromBrute(const std::vector<float>& brute, Vec3 n) const {
    std::vector<float> out = brute;
    const int k = pattern.per_texel;
    for (int m = 0; m < cubemap.size(); ++m) {
      if (brute[m] == 0) continue;
      double sum_c = 0;
      for (int j = 0; j < k; ++j) sum_c += std::max(0.0f, Dot(n, pattern.Direction(m, j)));
      const double all_visible = pattern.solid_angle[m] * sum_c / (k * std::numbers::pi);
      out[m] = static_cast<float>(ClippedTexelIrradiance(cubemap, m, n) * brute[m] / all_visible);
    }
    return out;
  }
};

double Sum(const std::vector<float>& row) { return std::accumulate(row.begin(), row.end(), 0.0); }

// ‖a − b‖ / ‖b‖.
double RelativeL2(const std::vector<float>& a, const std::vector<float>& b) {
  double d = 0, e = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    d += (double{a[i]} - b[i]) * (double{a[i]} - b[i]);
    e += double{b[i]} * b[i];
  }
  return std::sqrt(d / e);
}

// White furnace: with nothing occluding, every texel is decided visible or
// traced fully visible, and either way exactly I_m: the cosine-weighted
// solid angle of its part above the horizon (checked against the clipped
// Lambert integral in double), the horizon band included. So B = 1 up to
// float rounding — brute force's K rays per texel miss it by the quadrature
// error of the horizon band.
TEST(RefinedRowTest, WhiteFurnaceIsExact) {
  const Vec3 normals[] = {{0, 0, 1}, Normalize({1, 2, 3}), Normalize({-0.3f, 0.9f, -0.2f})};
  for (Vec3 n : normals) {
    const RayCaster caster = BuildOrDie(SceneOf({Quad({0, 0, 0}, n, 5)}));
    for (int res : {8, 16, 32}) {
      for (int k : {1, 4}) {
        const Rows rows(res, k);
        TransportStats stats, brute_stats;
        const std::vector<float> row = rows.Refined(caster, {0, 0, 0}, n, &stats);
        const std::vector<float> brute = rows.Brute(caster, {0, 0, 0}, n, &brute_stats);
        double unsampled = 0;  // slivers above the horizon that none of their rays reach
        for (int m = 0; m < rows.cubemap.size(); ++m) {
          const double exact = ClippedTexelIrradiance(rows.cubemap, m, n);
          if (row[m] == 0 && brute[m] == 0 && !rows.Above(m, n) && rows.RaysAbove(m, n) == 0) {
            unsampled += exact;
            continue;  // as brute force: no ray, no value
          }
          // float n·Φ_m: rounding relative to |Φ_m| ≈ Ω_m/π, not to the value.
          ASSERT_NEAR(row[m], exact, 1e-6 * rows.pattern.solid_angle[m])
              << "N=" << res << " m=" << m;
        }
        EXPECT_NEAR(Sum(row), 1 - unsampled, 1e-5) << "N=" << res << " K=" << k;
        EXPECT_EQ(stats.rays_occluded, 0u);
        // At N = 8 every texel is probed (the start spacing is N/8): with
        // K = 1 that is brute force's one ray each.
        EXPECT_LE(stats.rays_traced, brute_stats.rays_traced);
        if (k > 1) {
          EXPECT_LT(stats.rays_traced, brute_stats.rays_traced);
        }
      }
    }
  }
}

// Normal +z: all of −Z, none of +Z and half of each side face are below the
// horizon (brute force culls the same texels) and cost no rays; a floor
// under the sample would occlude any ray that went there.
TEST(RefinedRowTest, TexelsBelowTheHorizonAreZeroAndUntraced) {
  const RayCaster caster = BuildOrDie(SceneOf({Quad({0, 0, -1}, {0, 0, 1}, 100)}));
  for (int res : {8, 32}) {
    const Rows rows(res);
    TransportStats stats, brute;
    const std::vector<float> row = rows.Refined(caster, {0, 0, 0}, {0, 0, 1}, &stats);
    rows.Brute(caster, {0, 0, 0}, {0, 0, 1}, &brute);
    EXPECT_EQ(stats.texels_culled, 3ull * res * res);
    EXPECT_EQ(stats.texels_culled, brute.texels_culled);
    EXPECT_EQ(stats.rays_occluded, 0u);
    for (int m = 0; m < rows.cubemap.size(); ++m) {
      if (rows.cubemap.TexelOf(m).face != kNegZ) continue;
      ASSERT_EQ(row[m], 0.0f) << m;
    }
  }
}

// Σ_m T = 1 − r²/(r²+h²) for an opaque disk on the normal's axis (the
// closed form of TransportRowTest.DiskOnTheAxisBlocksItsProjectedSolidAngle).
TEST(RefinedRowTest, DiskOnTheAxisBlocksItsProjectedSolidAngle) {
  const Vec3 x{0.5f, -0.25f, 1};
  const Vec3 n = Normalize({0.2f, -0.1f, 1});
  for (float r_over_h : {0.5f, 1.0f, 2.0f}) {
    const float h = 1.5f, r = r_over_h * h;
    const RayCaster caster = BuildOrDie(SceneOf({Disk(x + n * h, -n, r, 512)}));
    const double expected = 1 - r * r / (r * r + h * h);
    for (int res : {32, 64}) {
      TransportStats stats;
      EXPECT_NEAR(Sum(Rows(res).Refined(caster, x, n, &stats)), expected, 0.005 * expected)
          << "r/h=" << r_over_h << " N=" << res;
      EXPECT_GT(stats.rays_occluded, 0u);
    }
  }
}

Scene DiskOverFloor() {
  return SceneOf({Quad({0, 0, 0}, {0, 0, 1}, 4), Disk({0.3f, 0, 1}, {0, 0, -1}, 0.8f, 64)});
}

std::vector<Vec3> FloorPoints() {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.push_back({-1.5f + 0.4f * i, 0.1f * i, 0});
  return points;
}

// Where visibility is smooth (a disk's silhouette), refinement classifies
// every texel as brute force's rays do: the rows equal brute force's rays
// valued exactly to float rounding, with a fraction of the rays — smaller
// the finer the cubemap, since silhouettes grow as N and the sphere as N².
TEST(RefinedRowTest, ClassifiesEveryTexelLikeBruteForceOnASmoothSilhouette) {
  const RayCaster caster = BuildOrDie(DiskOverFloor());
  double last_ratio = 1;
  for (int res : {16, 32, 64}) {
    const Rows rows(res);
    TransportStats brute, refined;
    for (Vec3 p : FloorPoints()) {
      const std::vector<float> b = rows.Brute(caster, p, {0, 0, 1}, &brute);
      const std::vector<float> r = rows.Refined(caster, p, {0, 0, 1}, &refined);
      EXPECT_LT(RelativeL2(r, rows.ExactFromBrute(b, {0, 0, 1})), 1e-6) << "N=" << res;
      // What the exact integral changes: brute force's quadrature noise.
      EXPECT_LT(RelativeL2(r, b), 0.02) << "N=" << res;
    }
    const double ratio = double(refined.rays_traced) / brute.rays_traced;
    EXPECT_LT(ratio, last_ratio) << "N=" << res;
    last_ratio = ratio;
  }
  EXPECT_LT(last_ratio, 0.12);  // N = 64
}

// A thin wire, 2.6 texels (2.3°) wide, across the +Z face along texel rows
// 25.2–27.8 of 64, between the rows 24 and 32 of a regular probe lattice of
// spacing 8 (each probe is in the first quarter of its texel).
// Brute force sees its shadow; naive coarse probing (regular lattice, no
// silhouette following) misses it entirely; staggered probes find it in a
// few blocks; following the silhouette from there traces all of it.
TEST(RefinedRowTest, ThinWireNeedsStaggeredProbesAndSilhouetteFollowing) {
  constexpr int kRes = 64;
  const float h = 1;
  // Texel rows 25.2..27.8 of the +Z face: t ∈ [25.2, 27.8]/64, direction
  // (sc, −tc, 1), so the wire at height h lies at y = −tc·h.
  const float y0 = -(2 * 25.2f / kRes - 1) * h, y1 = -(2 * 27.8f / kRes - 1) * h;
  Mesh wire;
  wire.name = "wire";
  wire.positions = {{-h, y0, h}, {h, y0, h}, {h, y1, h}, {-h, y1, h}};
  wire.triangles = {{0, 1, 2}, {0, 2, 3}};
  const RayCaster caster = BuildOrDie(SceneOf({wire}));
  const Vec3 x{0, 0, 0}, n{0, 0, 1};

  // The wire's shadow: Σ over the +Z face (all of it above the horizon) of
  // I_m − T[m], the cosine-weighted solid angle it hides.
  const Rows exact_rows(kRes);
  auto shadow_of = [&](const std::vector<float>& row) {
    double sum = 0;
    for (int m = 0; m < exact_rows.cubemap.size(); ++m)
      if (exact_rows.cubemap.TexelOf(m).face == kPosZ)
        sum += exact_rows.plan.IrradianceAt(m, n) - row[m];
    return sum;
  };
  const double shadow = shadow_of(exact_rows.ExactFromBrute(exact_rows.Brute(caster, x, n), n));
  ASSERT_GT(shadow, 0.01);  // the wire is there to find

  auto shadow_with = [&](RefineOptions o) {
    const Rows rows(kRes, 4, o);
    return shadow_of(rows.Refined(caster, x, n));
  };
  const double naive = shadow_with({.start_spacing = 8, .stagger = false, .follow = false});
  const double follow_only = shadow_with({.start_spacing = 8, .stagger = false, .follow = true});
  const double stagger_only = shadow_with({.start_spacing = 8, .stagger = true, .follow = false});
  const double guarded = shadow_with({.start_spacing = 8, .stagger = true, .follow = true});
  const double defaults = shadow_with({});
  std::printf(
      "wire shadow: brute force %.5f, naive %.5f, follow only %.5f, stagger only %.5f, "
      "both %.5f, defaults %.5f\n",
      shadow, naive, follow_only, stagger_only, guarded, defaults);
  EXPECT_EQ(naive, 0) << "a regular lattice misses the wire between its rows";
  EXPECT_EQ(follow_only, 0) << "nothing found, nothing to follow";
  EXPECT_GT(stagger_only, 0.05 * shadow);
  EXPECT_LT(stagger_only, 0.8 * shadow) << "found, but only near the probes that hit it";
  EXPECT_NEAR(guarded, shadow, 1e-4 * shadow);
  EXPECT_NEAR(defaults, shadow, 1e-4 * shadow);
}

TEST(RefinedRowTest, SameRowTwiceFromTwoThreadsAndReusedScratchIsBitIdentical) {
  const RayCaster caster = BuildOrDie(DiskOverFloor());
  const Rows rows(16, 4, {}, 77);
  const std::vector<Vec3> points = FloorPoints();
  std::vector<std::vector<float>> serial;
  for (Vec3 p : points) serial.push_back(rows.Refined(caster, p, {0, 0, 1}));
  RefineScratch reused;  // carries the previous row's state into the next
  for (size_t i = 0; i < points.size(); ++i)
    EXPECT_EQ(rows.Refined(caster, points[i], {0, 0, 1}, nullptr, reused), serial[i]) << i;
  std::vector<std::vector<float>> threaded[2];
  auto work = [&](int t) {
    RefineScratch scratch;
    for (int rep = 0; rep < 3; ++rep)
      for (Vec3 p : points)
        threaded[t].push_back(rows.Refined(caster, p, {0, 0, 1}, nullptr, scratch));
  };
  std::thread a(work, 0), b(work, 1);
  a.join();
  b.join();
  for (int t = 0; t < 2; ++t) {
    ASSERT_EQ(threaded[t].size(), 3 * points.size());
    for (size_t i = 0; i < threaded[t].size(); ++i)
      EXPECT_EQ(threaded[t][i], serial[i % points.size()]) << "thread " << t << " row " << i;
  }
}

TEST(RefinedRowTest, StatsAddUpOverRows) {
  const RayCaster caster = BuildOrDie(DiskOverFloor());
  const Rows rows(8);
  TransportStats one, both;
  rows.Refined(caster, {0, 0, 0}, {0, 0, 1}, &one);
  rows.Refined(caster, {0, 0, 0}, {0, 0, 1}, &both);
  rows.Refined(caster, {0, 0, 0}, {0, 0, 1}, &both);
  EXPECT_GT(one.rays_traced, 0u);
  EXPECT_GT(one.rays_occluded, 0u);
  EXPECT_EQ(both.rays_traced, 2 * one.rays_traced);
  EXPECT_EQ(both.rays_occluded, 2 * one.rays_occluded);
  EXPECT_EQ(both.texels_culled, 2 * one.texels_culled);
}

}  // namespace
}  // namespace refined_row_test
}  // namespace wavebake
