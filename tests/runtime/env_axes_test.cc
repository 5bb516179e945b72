// One bright pixel in a dark lat-long map must light the cube texels around
// the direction the documented convention (latlong.h) gives that pixel:
// row 0 is +Y, the image centre −Z, u = ¾ is +X, u = ¼ −X, the seam +Z.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "env_test_util.h"
#include "runtime/env/env_resample.h"

namespace wavebake {
namespace {

using testing::CubeEnergy;

constexpr int kW = 64, kH = 32;

struct BrightPixelCase {
  const char* axis;
  int x, y;  // the pixel
  int face;  // the cube face its direction must land on
};

// The pixel-centre direction written out from the convention, not taken
// from the code under test.
Vec3 PixelDirection(int x, int y) {
  const double theta = std::numbers::pi * (y + 0.5) / kH;
  const double phi = std::numbers::pi * (2 * (x + 0.5) / kW - 1);
  return Vec3{static_cast<float>(std::sin(theta) * std::sin(phi)),
              static_cast<float>(std::cos(theta)),
              static_cast<float>(-std::sin(theta) * std::cos(phi))};
}

class BrightPixelTest : public ::testing::TestWithParam<BrightPixelCase> {};

TEST_P(BrightPixelTest, LandsOnTheFaceOfItsDirection) {
  const BrightPixelCase& p = GetParam();
  EnvMap env = testing::UniformEnv(kW, kH, 0);
  testing::SetPixel(env, p.x, p.y, {1000, 1000, 1000});
  const Cubemap cube(8);
  const std::vector<float> l = ResampleToCubemap(env, cube);
  const double total = CubeEnergy(l, cube, 0);
  EXPECT_NEAR(total, SphereIntegral(env, 0), 1e-6 * total);
  EXPECT_GT(CubeEnergy(l, cube, 0, p.face), 0.99 * total) << p.axis;
}

// With texels finer than the pixel, the light stays on the pixel's
// footprint and mostly fills the texel its centre direction falls in.
TEST_P(BrightPixelTest, StaysOnItsFootprint) {
  const BrightPixelCase& p = GetParam();
  EnvMap env = testing::UniformEnv(kW, kH, 0);
  testing::SetPixel(env, p.x, p.y, {1000, 1000, 1000});
  const Cubemap cube(32);
  const std::vector<float> l = ResampleToCubemap(env, cube);
  const Vec3 d = PixelDirection(p.x, p.y);
  // Except at the poles, where a pixel is a wedge thinner than a texel.
  const bool wedge = p.y == 0 || p.y == kH - 1;
  EXPECT_GT(l[3 * cube.Lookup(d)], wedge ? 0.0f : 250.0f) << p.axis;
  // A texel touching the pixel has its centre within the pixel's extent
  // (π/kH in θ, no more in φ) plus the texel's half-diagonal (< 2.5°).
  const double reach = std::numbers::pi / kH + 2.5 * std::numbers::pi / 180;
  for (int m = 0; m < cube.size(); ++m) {
    if (l[3 * m] == 0) continue;
    EXPECT_LT(std::acos(std::min(1.0f, Dot(cube.TexelCenter(m), d))), reach)
        << p.axis << ": light in texel " << m;
  }
}

INSTANTIATE_TEST_SUITE_P(Axes, BrightPixelTest,
                         ::testing::Values(BrightPixelCase{"zenith", 10, 0, kPosY},
                                           BrightPixelCase{"nadir", 40, kH - 1, kNegY},
                                           BrightPixelCase{"+X", 3 * kW / 4, kH / 2, kPosX},
                                           BrightPixelCase{"-X", kW / 4, kH / 2 - 1, kNegX},
                                           BrightPixelCase{"-Z", kW / 2, kH / 2, kNegZ},
                                           BrightPixelCase{"+Z", 0, kH / 2 - 1, kPosZ}),
                         [](const auto& info) {
                           const std::string axis = info.param.axis;
                           return axis[0] == '+' ? "Pos" + axis.substr(1)
                                                 : (axis[0] == '-' ? "Neg" + axis.substr(1) : axis);
                         });

}  // namespace
}  // namespace wavebake
