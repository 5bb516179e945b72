// The cubemap of light directions (DESIGN.md §1 "Directions") against the
// OpenGL cube-map table, numerical integration of the solid-angle Jacobian,
// and the 4π of the sphere.
#include "core/directions/cubemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace wavebake {
namespace {

TEST(CubemapTest, SolidAnglesSumToFourPi) {
  for (int n = 1; n <= 64; ++n) {
    const Cubemap cube(n);
    double sum = 0;
    for (int m = 0; m < cube.size(); ++m) sum += cube.SolidAngle(m);
    EXPECT_NEAR(sum, 4 * M_PI, 1e-6 * 4 * M_PI) << "N=" << n;
  }
}

// ∫∫ dA / (1 + x² + y²)^{3/2} over the texel's square on the face plane at
// distance 1 (x, y ∈ [−1, 1]), midpoint rule on a sub × sub grid.
double IntegratedSolidAngle(int n, int tx, int ty, int sub) {
  const double x0 = 2.0 * tx / n - 1, y0 = 2.0 * ty / n - 1, h = 2.0 / n / sub;
  double sum = 0;
  for (int j = 0; j < sub; ++j) {
    for (int i = 0; i < sub; ++i) {
      const double x = x0 + (i + 0.5) * h, y = y0 + (j + 0.5) * h;
      const double q = 1 + x * x + y * y;
      sum += 1 / (q * std::sqrt(q));
    }
  }
  return sum * h * h;
}

TEST(CubemapTest, SolidAngleMatchesNumericalIntegration) {
  for (const int n : {1, 4, 16}) {
    const Cubemap cube(n);
    for (const auto& [tx, ty] :
         {std::pair{0, 0}, std::pair{n - 1, 0}, std::pair{n / 2, n / 2}, std::pair{n / 3, n - 1}}) {
      for (const int face : {kPosX, kNegY, kNegZ}) {
        const double exact = cube.SolidAngle(cube.Index({face, tx, ty}));
        // Midpoint rule error ~ h²/24 · f''/f ≲ 3e-6 relative at 400×400
        // (h = 2/N/400), so 1e-5 separates it from any formula error.
        EXPECT_NEAR(exact, IntegratedSolidAngle(n, tx, ty, 400), 1e-5 * exact)
            << "N=" << n << " texel " << tx << "," << ty;
      }
    }
  }
}

TEST(CubemapTest, CornerTexelsSmallerThanCentreTexels) {
  const Cubemap cube(16);
  const double corner = cube.SolidAngle(cube.Index({kPosZ, 0, 0}));
  const double centre = cube.SolidAngle(cube.Index({kPosZ, 8, 8}));
  EXPECT_LT(corner, centre);
  // Centre texel ≈ its flat area (2/N)² at distance ~1; corner ≈ area / 3^{3/2}.
  EXPECT_NEAR(centre, std::pow(2.0 / 16, 2), 0.02 * centre);
  EXPECT_NEAR(corner, std::pow(2.0 / 16, 2) / std::pow(1 + 2 * std::pow(15.0 / 16, 2), 1.5),
              0.05 * corner);
}

TEST(CubemapTest, LookupOfTexelCentreIsIdentity) {
  const Cubemap cube(16);
  for (int m = 0; m < cube.size(); ++m) ASSERT_EQ(cube.Lookup(cube.TexelCenter(m)), m) << m;
}

TEST(CubemapTest, LookupOfPointsInsideTexelFindsIt) {
  const Cubemap cube(8);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.02, 0.98);
  for (int m = 0; m < cube.size(); ++m) {
    const Texel t = cube.TexelOf(m);
    for (int k = 0; k < 4; ++k) {
      const Vec3 d = Cubemap::FaceDirection(t.face, (t.x + u(rng)) / 8, (t.y + u(rng)) / 8);
      // Lookup must not need normalized input.
      ASSERT_EQ(cube.Lookup(d * 3.5f), m) << m;
    }
  }
}

TEST(CubemapTest, DirectionsAreUnitLength) {
  const Cubemap cube(32);
  for (int m = 0; m < cube.size(); ++m) ASSERT_NEAR(Length(cube.TexelCenter(m)), 1.0f, 1e-6f);
}

TEST(CubemapTest, IndexAndTexelOfAreInverse) {
  const Cubemap cube(8);
  EXPECT_EQ(cube.size(), 6 * 64);
  for (int m = 0; m < cube.size(); ++m) ASSERT_EQ(cube.Index(cube.TexelOf(m)), m);
  EXPECT_EQ(cube.Index({kNegY, 3, 5}), 3 * 64 + 5 * 8 + 3);  // m = face·N² + y·N + x
}

// OpenGL 4.6 §8.13 table 8.19, as (major axis, direction of growing s,
// direction of growing t): sc = −rz/+rz/+rx/+rx/+rx/−rx and tc = −ry/−ry/
// +rz/−rz/−ry/−ry for +X −X +Y −Y +Z −Z.
struct FaceAxes {
  Vec3 major, s_axis, t_axis;
};
constexpr FaceAxes kGlTable[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
    {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},   {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
    {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}},
};

TEST(CubemapTest, FaceOrientationFollowsOpenGlTable) {
  for (int face = 0; face < 6; ++face) {
    const FaceAxes& a = kGlTable[face];
    for (const auto& [s, t] : {std::pair{0.5, 0.5}, std::pair{0.1, 0.8}, std::pair{0.9, 0.2}}) {
      const Vec3 expected =
          Normalize(a.major + a.s_axis * float(2 * s - 1) + a.t_axis * float(2 * t - 1));
      const Vec3 d = Cubemap::FaceDirection(face, s, t);
      EXPECT_NEAR(d.x, expected.x, 1e-6);
      EXPECT_NEAR(d.y, expected.y, 1e-6);
      EXPECT_NEAR(d.z, expected.z, 1e-6);
    }
  }
  // Spot checks from the brief: +X texel (0,0) looks to +z, +y; face centres
  // are the axes.
  const Cubemap cube(4);
  const Vec3 px00 = cube.TexelCenter(cube.Index({kPosX, 0, 0}));
  EXPECT_GT(px00.x, 0);
  EXPECT_GT(px00.y, 0);
  EXPECT_GT(px00.z, 0);
  EXPECT_EQ(Cubemap::FaceDirection(kPosY, 0.5, 0.5), (Vec3{0, 1, 0}));
  EXPECT_EQ(Cubemap::FaceDirection(kNegZ, 0.5, 0.5), (Vec3{0, 0, -1}));
}

TEST(CubemapTest, FacesMeetAlongSharedEdges) {
  // Every edge point of a face must also be an edge point of the neighbour
  // face, so the six faces tile the sphere without gaps or flips: the point
  // just beyond an edge looks up into the adjacent face, at the edge texel.
  const Cubemap cube(8);
  for (int face = 0; face < 6; ++face) {
    for (const auto& [s, t] :
         {std::pair{0.0, 0.5}, std::pair{1.0, 0.5}, std::pair{0.5, 0.0}, std::pair{0.5, 1.0}}) {
      const Vec3 edge = Cubemap::FaceDirection(face, s, t);
      // Beyond the edge: the face plane extrapolated a little further out.
      const Vec3 beyond =
          Cubemap::FaceDirection(face, 0.5 + 1.02 * (s - 0.5), 0.5 + 1.02 * (t - 0.5));
      const Texel other = cube.TexelOf(cube.Lookup(beyond));
      EXPECT_NE(other.face, face);
      const bool on_edge = other.x == 0 || other.x == 7 || other.y == 0 || other.y == 7;
      EXPECT_TRUE(on_edge) << face;
      // The edge point itself is on the boundary of both faces: |major| ties.
      const float big = std::max({std::fabs(edge.x), std::fabs(edge.y), std::fabs(edge.z)});
      int ties = 0;
      for (const float c : {edge.x, edge.y, edge.z}) ties += std::fabs(std::fabs(c) - big) < 1e-6f;
      EXPECT_EQ(ties, 2) << face;
    }
  }
}

}  // namespace
}  // namespace wavebake
