#include "core/directions/texel_irradiance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace wavebake {
namespace {

// The same integral by the midpoint rule on the face plane, sharing nothing
// with Lambert's formula: a texel is a square of the cube face [-1,1]², a
// point p on it subtends dω = dA/|p|³ and n·ω = n·p/|p|, so
// I = (1/π) ∫ max(0, n·p)/|p|⁴ dA.
double MidpointIrradiance(const Cubemap& cubemap, int m, Vec3 n, int steps) {
  const Texel t = cubemap.TexelOf(m);
  const double k = cubemap.n(), area = 4.0 / (k * k * steps * steps);
  double sum = 0;
  for (int j = 0; j < steps; ++j) {
    for (int i = 0; i < steps; ++i) {
      const auto p =
          Cubemap::FacePoint(t.face, (t.x + (i + 0.5) / steps) / k, (t.y + (j + 0.5) / steps) / k);
      const double r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
      sum += std::max(0.0, n.x * p[0] + n.y * p[1] + n.z * p[2]) / (r2 * r2);
    }
  }
  return sum * area / std::numbers::pi;
}

const Vec3 kNormals[] = {{0, 0, 1},
                         {1, 0, 0},
                         Normalize({1, 2, 3}),
                         Normalize({-0.3f, 0.9f, -0.2f}),
                         Normalize({0.577f, -0.577f, 0.578f})};

// White furnace in closed form: the clipped texels tile the hemisphere, and
// (1/π) ∫_{n·ω>0} n·ω dω = |n| (1 up to the float normal's rounding).
TEST(TexelIrradianceTest, ClippedTexelsSumToOne) {
  for (int res : {1, 2, 8, 32}) {
    const Cubemap cubemap(res);
    for (Vec3 n : kNormals) {
      double sum = 0;
      for (int m = 0; m < cubemap.size(); ++m) sum += ClippedTexelIrradiance(cubemap, m, n);
      const double length = std::sqrt(double{n.x} * n.x + double{n.y} * n.y + double{n.z} * n.z);
      EXPECT_NEAR(sum, length, 1e-12) << "N=" << res << " n=" << n.x << "," << n.y << "," << n.z;
    }
  }
}

// The +Z face seen along +Z: (1/π)·4·acos(1/3)·(1/√2)/2, Lambert by hand.
TEST(TexelIrradianceTest, WholeFaceMatchesTheHandComputedValue) {
  const Cubemap one(1);
  const double expected = 2 * std::acos(1.0 / 3) / std::sqrt(2.0) / std::numbers::pi;
  EXPECT_NEAR(ClippedTexelIrradiance(one, one.Index({kPosZ, 0, 0}), {0, 0, 1}), expected, 1e-14);
  EXPECT_NEAR(MidpointIrradiance(one, one.Index({kPosZ, 0, 0}), {0, 0, 1}, 2000), expected, 1e-6);
}

// Against the independent midpoint rule, for texels above, across and below
// the horizon.
TEST(TexelIrradianceTest, MatchesTheMidpointRule) {
  const Cubemap cubemap(8);
  const std::vector<Vec3> phi = TexelIrradianceVectors(cubemap);
  int crossing = 0;
  for (Vec3 n : kNormals) {
    for (int m = 0; m < cubemap.size(); m += 7) {
      const double exact = ClippedTexelIrradiance(cubemap, m, n);
      const double numeric = MidpointIrradiance(cubemap, m, n, 400);
      // The midpoint rule's error: O(h²) where smooth, O(h) on the horizon kink.
      EXPECT_NEAR(exact, numeric, 2e-6 * cubemap.SolidAngle(m)) << "m=" << m;
      if (exact > 1e-9 && std::abs(exact - Dot(n, phi[m])) > 1e-3 * exact) ++crossing;
    }
  }
  EXPECT_GT(crossing, 0);  // the clipping was exercised
}

// A texel with all four corners above the horizon: the linear form n·Φ_m.
TEST(TexelIrradianceTest, VectorFormEqualsTheClippedIntegralAboveTheHorizon) {
  const Cubemap cubemap(16);
  const std::vector<Vec3> phi = TexelIrradianceVectors(cubemap);
  int above = 0;
  for (Vec3 n : kNormals) {
    for (int m = 0; m < cubemap.size(); ++m) {
      const Texel t = cubemap.TexelOf(m);
      bool all_above = true;
      for (int c = 0; c < 4; ++c) {
        const auto p = Cubemap::FacePoint(t.face, (t.x + c % 2) / 16.0, (t.y + c / 2) / 16.0);
        all_above &= n.x * p[0] + n.y * p[1] + n.z * p[2] > 0;
      }
      if (!all_above) continue;
      ++above;
      const double exact = ClippedTexelIrradiance(cubemap, m, n);
      EXPECT_NEAR(Dot(n, phi[m]), exact, 1e-6 * exact) << "m=" << m;
    }
  }
  EXPECT_GT(above, 1000);
}

}  // namespace
}  // namespace wavebake
