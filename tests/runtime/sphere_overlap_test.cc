// The pixel/texel overlap matrix against closed forms: its sums are the
// exact solid angles of core/directions/cubemap.h and latlong.h, and it averages a
// linear field as Lambert's vector-irradiance formula says it must.
#include "runtime/env/sphere_overlap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "runtime/env/env_resample.h"
#include "runtime/env/latlong.h"

namespace wavebake {
namespace {

struct Grid {
  int width, height, n;
};

class OverlapSumsTest : public ::testing::TestWithParam<Grid> {};

TEST_P(OverlapSumsTest, SumsAreTheExactSolidAngles) {
  const Grid g = GetParam();
  const Cubemap cube(g.n);
  const SphereOverlap overlap(g.width, g.height, cube);
  for (int m = 0; m < cube.size(); ++m) {
    ASSERT_NEAR(overlap.TexelArea(m) / cube.SolidAngle(m), 1, 1e-9) << "texel " << m;
  }
  for (int p = 0; p < g.width * g.height; ++p) {
    ASSERT_NEAR(overlap.PixelArea(p) / LatLongPixelSolidAngle(p / g.width, g.width, g.height), 1,
                1e-9)
        << "pixel (" << p % g.width << ", " << p / g.width << ")";
  }
}

INSTANTIATE_TEST_SUITE_P(Grids, OverlapSumsTest,
                         ::testing::Values(Grid{256, 128, 16}, Grid{256, 128, 64}, Grid{64, 32, 8},
                                           Grid{128, 64, 32},
                                           Grid{36, 18, 16},  // no column on a face edge
                                           Grid{16, 8, 64},   // pixels ≫ texels
                                           Grid{16, 8, 1},    // the pole inside a texel
                                           Grid{4, 2, 2}));

// ∫ d dω over a spherical polygon is ½ Σ_edges γ_e n̂_e (γ_e the edge's
// angle, n̂_e the unit normal of its great circle): Lambert's formula.
Vec3 LambertVectorIntegral(const Cubemap& cube, int m) {
  const Texel t = cube.TexelOf(m);
  const double n = cube.n();
  const Vec3 v[4] = {Cubemap::FaceDirection(t.face, t.x / n, t.y / n),
                     Cubemap::FaceDirection(t.face, (t.x + 1) / n, t.y / n),
                     Cubemap::FaceDirection(t.face, (t.x + 1) / n, (t.y + 1) / n),
                     Cubemap::FaceDirection(t.face, t.x / n, (t.y + 1) / n)};
  Vec3 sum;
  for (int i = 0; i < 4; ++i) {
    const Vec3 a = v[i], b = v[(i + 1) % 4];
    sum = sum + Normalize(Cross(a, b)) * (0.5f * std::acos(std::min(1.0f, Dot(a, b))));
  }
  return Dot(sum, cube.TexelCenter(m)) < 0 ? -sum : sum;  // the winding's sign
}

// Each pixel of the map holds the exact mean of L(d) = 1 + a·d over it.
EnvMap LinearField(int width, int height, Vec3 a) {
  EnvMap env{width, height, std::vector<float>(size_t(width) * height * 3)};
  const double dphi = 2 * std::numbers::pi / width;
  for (int y = 0; y < height; ++y) {
    const double t0 = std::numbers::pi * y / height, t1 = std::numbers::pi * (y + 1) / height;
    const double band = std::cos(t0) - std::cos(t1);
    const double sin2 = (t1 - t0) / 2 - (std::sin(2 * t1) - std::sin(2 * t0)) / 4;  // ∫ sin²θ
    const double ycos = (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) / 2;
    for (int x = 0; x < width; ++x) {
      const double p0 = -std::numbers::pi + x * dphi, p1 = p0 + dphi;
      const double ix = sin2 * (std::cos(p0) - std::cos(p1));
      const double iz = -sin2 * (std::sin(p1) - std::sin(p0));
      const double mean = 1 + (a.x * ix + a.y * ycos * dphi + a.z * iz) / (band * dphi);
      for (int c = 0; c < 3; ++c) env.rgb[(size_t(y) * width + x) * 3 + c] = float(mean);
    }
  }
  return env;
}

TEST(OverlapTest, TexelMeansOfALinearFieldFollowLambert) {
  const Vec3 a{0.3f, -0.5f, 0.4f};
  const EnvMap env = LinearField(512, 256, a);
  const Cubemap cube(8);
  const std::vector<float> area = ResampleToCubemap(env, cube);
  const std::vector<float> point = PointSampleToCubemap(env, cube);
  double worst_area = 0, worst_point = 0;
  for (int m = 0; m < cube.size(); ++m) {
    const double expected = 1 + Dot(a, LambertVectorIntegral(cube, m)) / cube.SolidAngle(m);
    worst_area = std::max(worst_area, std::fabs(area[3 * m] - expected));
    worst_point = std::max(worst_point, std::fabs(point[3 * m] - expected));
  }
  // What is left is the pixelation of the field along texel edges (~1e-4 at
  // 0.7° pixels); the texel centre misses the mean by ~1e-2.
  EXPECT_LT(worst_area, 3e-4);
  EXPECT_GT(worst_point, 10 * worst_area);
}

}  // namespace
}  // namespace wavebake
