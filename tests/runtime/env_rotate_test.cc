// Rotated(): a quarter turn about +Y, counter-clockwise seen from above.
#include <gtest/gtest.h>

#include <cstring>

#include "env_test_util.h"
#include "runtime/env/env_resample.h"

namespace wavebake {
namespace {

using testing::CubeEnergy;
using testing::ProbePath;

TEST(RotateTest, FullTurnsAreTheIdentity) {
  const absl::StatusOr<EnvMap> env = LoadEnvMap(ProbePath("grace.hdr"));
  ASSERT_TRUE(env.ok()) << env.status();
  for (double degrees : {0.0, 360.0, -360.0, 720.0}) {
    const EnvMap r = Rotated(*env, degrees);
    ASSERT_EQ(r.width, env->width);
    ASSERT_EQ(r.height, env->height);
    for (size_t i = 0; i < r.rgb.size(); ++i) {
      ASSERT_NEAR(r.rgb[i], env->rgb[i], 1e-6f * env->rgb[i]) << degrees << "° value " << i;
    }
  }
}

TEST(RotateTest, TwoHalfTurnsAreAFullTurn) {
  const absl::StatusOr<EnvMap> env = LoadEnvMap(ProbePath("pisa.hdr"));
  ASSERT_TRUE(env.ok()) << env.status();
  const EnvMap r = Rotated(Rotated(*env, 180), 180);
  for (size_t i = 0; i < r.rgb.size(); ++i) ASSERT_NEAR(r.rgb[i], env->rgb[i], 1e-6f * env->rgb[i]);
}

// +90° (counter-clockwise from above) carries +X to −Z; −90° carries it to +Z.
TEST(RotateTest, QuarterTurnMovesPlusXToMinusZ) {
  EnvMap env = testing::UniformEnv(64, 32, 0);
  testing::SetPixel(env, 48, 16, {500, 500, 500});  // just past u = ¾: +X
  const Cubemap cube(8);
  const std::vector<float> before = ResampleToCubemap(env, cube);
  const double total = CubeEnergy(before, cube, 0);
  ASSERT_GT(CubeEnergy(before, cube, 0, kPosX), 0.99 * total);
  const std::vector<float> ccw = ResampleToCubemap(Rotated(env, 90), cube);
  EXPECT_GT(CubeEnergy(ccw, cube, 0, kNegZ), 0.99 * total);
  const std::vector<float> cw = ResampleToCubemap(Rotated(env, -90), cube);
  EXPECT_GT(CubeEnergy(cw, cube, 0, kPosZ), 0.99 * total);
}

TEST(RotateTest, KeepsTheSphereIntegral) {
  const absl::StatusOr<EnvMap> env = LoadEnvMap(ProbePath("grace.hdr"));
  ASSERT_TRUE(env.ok()) << env.status();
  for (double degrees : {37.3, 90.0, -123.45, 200.0}) {
    const EnvMap r = Rotated(*env, degrees);
    for (int c = 0; c < 3; ++c) {
      const double expected = SphereIntegral(*env, c);
      EXPECT_NEAR(SphereIntegral(r, c), expected, 1e-5 * expected) << degrees << "°";
    }
  }
}

}  // namespace
}  // namespace wavebake
