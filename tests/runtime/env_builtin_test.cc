// builtin:sky against the closed-form integral documented in env_builtin.h,
// and its sun where the convention puts it.
#include "runtime/env/env_builtin.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "env_test_util.h"
#include "runtime/env/env_resample.h"

namespace wavebake {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

double ExpectedSkyIntegral(const SkyParams& p, int c) {
  const double sun = 2 * std::numbers::pi * (1 - std::cos(p.sun_radius * kDeg)) * p.sun[c];
  const double area =
      (p.area_azimuth_max - p.area_azimuth_min) * kDeg *
      (std::sin(p.area_elevation_max * kDeg) - std::sin(p.area_elevation_min * kDeg)) *
      p.area_light[c];
  return std::numbers::pi * (p.zenith[c] + p.horizon[c]) + 2 * std::numbers::pi * p.ground[c] +
         sun + area;
}

TEST(SkyTest, IntegralMatchesClosedForm) {
  const absl::StatusOr<EnvMap> env = LoadEnvMap("builtin:sky");
  ASSERT_TRUE(env.ok()) << env.status();
  ASSERT_EQ(env->width, 2 * env->height);
  const SkyParams p;
  const Cubemap cube(32);
  const std::vector<float> l = ResampleToCubemap(*env, cube);
  for (int c = 0; c < 3; ++c) {
    const double expected = ExpectedSkyIntegral(p, c);
    EXPECT_NEAR(SphereIntegral(*env, c), expected, 1e-3 * expected) << "channel " << c;
    EXPECT_NEAR(testing::CubeEnergy(l, cube, c), expected, 1e-3 * expected) << "channel " << c;
  }
}

TEST(SkyTest, SunIsInTheTexelOfItsDirection) {
  const SkyParams p;
  const EnvMap env = MakeSkyEnv(p);
  const Cubemap cube(16);
  const std::vector<float> l = ResampleToCubemap(env, cube);
  int brightest = 0;
  for (int m = 0; m < cube.size(); ++m) {
    if (l[3 * m] > l[3 * brightest]) brightest = m;
  }
  const double elevation = p.sun_elevation * kDeg, azimuth = p.sun_azimuth * kDeg;
  // Azimuth 0 looks down −Z and +90° is +X (latlong.h).
  const Vec3 sun{static_cast<float>(std::cos(elevation) * std::sin(azimuth)),
                 static_cast<float>(std::sin(elevation)),
                 static_cast<float>(-std::cos(elevation) * std::cos(azimuth))};
  EXPECT_EQ(brightest, cube.Lookup(sun));
}

TEST(SkyTest, EveryTexelIsFiniteAndPositive) {
  const EnvMap env = MakeSkyEnv();
  for (float v : env.rgb) ASSERT_TRUE(std::isfinite(v) && v > 0);
}

}  // namespace
}  // namespace wavebake
