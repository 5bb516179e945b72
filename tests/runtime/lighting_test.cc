// The lighting side (runtime/relight/row_basis.h, runtime/relight/lighting.h): the row
// transform is the bake's (orthonormal, so T·L is basis independent), the
// support solid angles tile the sphere, and the selection is the
// area-weighted top n.
#include "runtime/relight/lighting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/directions/cubemap.h"
#include "core/wavelets/wavelet2d.h"
#include "runtime/env/env_map.h"
#include "runtime/env/env_resample.h"
#include "runtime/relight/row_basis.h"
#include "tests/runtime/env_test_util.h"

namespace wavebake {
namespace {

constexpr double kFourPi = 4 * std::numbers::pi;

std::vector<float> RandomCube(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<float> v(3 * 6 * n * n);
  for (float& x : v) x = u(rng);
  return v;
}

// Parseval: an orthonormal row filter keeps every dot product, so
// Σ_m T_m L_m of a (one-channel) row is the same in pixels and coefficients.
TEST(RowBasis, OrthonormalFiltersKeepTheDotProduct) {
  for (WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kDaub4}) {
    const int n = 16;
    std::vector<float> light = RandomCube(n, 1), row = RandomCube(n, 2);
    double pixel_dot = 0;
    for (size_t i = 0; i < light.size(); ++i) pixel_dot += double{light[i]} * row[i];
    RowTransformCube(f, n, light);
    RowTransformCube(f, n, row);
    double wavelet_dot = 0;
    for (size_t i = 0; i < light.size(); ++i) wavelet_dot += double{light[i]} * row[i];
    EXPECT_NEAR(wavelet_dot, pixel_dot, 1e-5 * std::fabs(pixel_dot));
  }
}

// The layout is the bake's: per face and channel, Forward2d of the N×N face
// image, coefficient (x, y) at m = face*N*N + y*N + x; and it inverts.
TEST(RowBasis, PerFaceMallatLayoutAndInverse) {
  const int n = 8;
  const std::vector<float> cube = RandomCube(n, 3);
  std::vector<float> rgb = cube;
  RowTransformCube(WaveletFilter::kHaar, n, rgb);
  for (int face = 0; face < 6; ++face) {
    for (int c = 0; c < 3; ++c) {
      std::vector<float> img(n * n);
      for (int i = 0; i < n * n; ++i) img[i] = cube[3 * (face * n * n + i) + c];
      Forward2d(WaveletFilter::kHaar, img, n, n, 3);
      for (int i = 0; i < n * n; ++i) ASSERT_EQ(rgb[3 * (face * n * n + i) + c], img[i]);
    }
  }
  InverseRowTransformCube(WaveletFilter::kHaar, n, rgb);
  for (size_t i = 0; i < rgb.size(); ++i) EXPECT_NEAR(rgb[i], cube[i], 1e-6);
}

// A constant L has only the six scaling coefficients, N·L each (the
// orthonormal scaling function of an N×N face is 1/N per texel).
TEST(RowBasis, ConstantLightingIsSixScalingCoefficients) {
  const int n = 16;
  LightingCoefficients l =
      ProjectLighting(std::vector<float>(3 * 6 * n * n, 2.0f), n, WaveletFilter::kHaar);
  for (int m = 0; m < 6 * n * n; ++m) {
    const bool scaling = m % (n * n) == 0;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(l.rgb[3 * m + c], scaling ? 2.0f * n : 0.0f, 1e-4) << m;
    }
  }
  auto lights = SelectWaveletLights(l, 100);
  ASSERT_TRUE(lights.ok());
  EXPECT_EQ(lights->lights.size(), 6u);  // zeros are never chosen
}

TEST(RowBasis, BandsFollowSupportSize) {
  EXPECT_EQ(RowBand(0, 0), 0);  // scaling
  EXPECT_EQ(RowBand(1, 0), 0);  // the coarsest wavelets share the face-sized support
  EXPECT_EQ(RowBand(1, 1), 0);
  EXPECT_EQ(RowBand(2, 3), 1);
  EXPECT_EQ(RowBand(0, 7), 2);
  EXPECT_EQ(RowBand(63, 5), 5);
  EXPECT_EQ(RowBandCount(64), 6);  // Overbeck §6.1: 6 bands at 64×64
  EXPECT_EQ(RowBandCount(8), 3);
}

// Support blocks of one orientation and level tile a face: each level sums to
// 4π/6 per orientation; the scaling function's support is the whole face,
// and a finest-level wavelet covers 2×2 texels.
TEST(RowBasis, SupportSolidAnglesTileTheFace) {
  const int n = 16;
  const Cubemap cube(n);
  const std::vector<float> s = SupportSolidAngles(n);
  for (int face = 0; face < 6; ++face) {
    const int base = face * n * n;
    EXPECT_NEAR(s[base], kFourPi / 6, 1e-5);
    for (int level = 1; level <= 4; ++level) {
      const int half = 1 << (level - 1);
      double hl = 0, lh = 0, hh = 0;
      for (int y = 0; y < half; ++y) {
        for (int x = 0; x < half; ++x) {
          hl += s[base + y * n + half + x];
          lh += s[base + (half + y) * n + x];
          hh += s[base + (half + y) * n + half + x];
        }
      }
      EXPECT_NEAR(hl, kFourPi / 6, 1e-5) << level;
      EXPECT_NEAR(lh, kFourPi / 6, 1e-5) << level;
      EXPECT_NEAR(hh, kFourPi / 6, 1e-5) << level;
    }
    // Finest HH at (n/2 + 3, n/2 + 5) covers texels (6..7, 10..11).
    double block = 0;
    for (int y = 10; y < 12; ++y)
      for (int x = 6; x < 8; ++x) block += cube.SolidAngle(base + y * n + x);
    EXPECT_NEAR(s[base + (n / 2 + 5) * n + n / 2 + 3], block, 1e-7);
  }
}

// Ng et al. 2003 area weighting: of two coefficients of equal magnitude the
// one with the larger support wins; selection is by |rgb|·Ω, descending.
TEST(Lighting, SelectionIsAreaWeightedTopN) {
  const int n = 8;
  LightingCoefficients l{n, WaveletFilter::kHaar, std::vector<float>(3 * 6 * n * n, 0.0f)};
  auto set = [&](int m, float r, float g, float b) {
    l.rgb[3 * m] = r, l.rgb[3 * m + 1] = g, l.rgb[3 * m + 2] = b;
  };
  set(7 * 8 + 7, 3, 0, 0);        // finest level, one texel of support
  set(1 * 8 + 1, 0, 0, -3);       // level 1: the whole face
  set(2 * 8 + 3, 0, 1, 0);        // level 2: a quarter face
  set(64 + 0, 0.5f, 0.5f, 0.5f);  // face 1 scaling, |rgb| = 0.87
  auto top = SelectWaveletLights(l, 3);
  ASSERT_TRUE(top.ok());
  ASSERT_EQ(top->lights.size(), 3u);
  EXPECT_EQ(top->lights[0].column, 9u);
  EXPECT_EQ(top->lights[0].weight[2], -3.0f);
  EXPECT_EQ(top->lights[1].column, 64u);  // 0.87·(4π/6) > 1·(4π/24)
  EXPECT_EQ(top->lights[2].column, 19u);
  auto all = SelectWaveletLights(l, 1000);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->lights.size(), 4u);
  EXPECT_EQ(all->lights[3].column, 63u);
}

TEST(Lighting, TermsMustBePositive) {
  LightingCoefficients l{8, WaveletFilter::kHaar, std::vector<float>(3 * 384, 1.0f)};
  for (int bad : {0, -5}) {
    auto r = SelectWaveletLights(l, bad);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find("terms"), std::string_view::npos);
  }
}

// One projector serves every frame of a rotation, in any order, and each
// frame's lighting is what a fresh resampling of that frame gives.
TEST(EnvProjector, ReusedAcrossFramesMatchesAFreshResamplingOfEach) {
  absl::StatusOr<EnvMap> env = LoadEnvMap(testing::ProbePath("grace.hdr"));
  ASSERT_TRUE(env.ok()) << env.status();
  constexpr int kN = 8;
  absl::StatusOr<EnvProjector> projector =
      EnvProjector::Create(env->width, env->height, kN, WaveletFilter::kHaar);
  ASSERT_TRUE(projector.ok()) << projector.status();
  for (double degrees : {37.0, 0.0, 271.5, 37.0}) {
    const EnvMap frame = Rotated(*env, degrees);
    absl::StatusOr<LightingCoefficients> got = projector->Project(frame);
    ASSERT_TRUE(got.ok()) << got.status();
    const LightingCoefficients fresh =
        ProjectLighting(ResampleToCubemap(frame, Cubemap(kN)), kN, WaveletFilter::kHaar);
    EXPECT_EQ(got->rgb, fresh.rgb) << degrees << " degrees";
  }
}

TEST(EnvProjector, RefusesAMapOfAnotherSize) {
  absl::StatusOr<EnvProjector> projector = EnvProjector::Create(16, 8, 8, WaveletFilter::kHaar);
  ASSERT_TRUE(projector.ok()) << projector.status();
  absl::StatusOr<LightingCoefficients> got = projector->Project(testing::UniformEnv(32, 16, 1));
  EXPECT_EQ(got.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(got.status().message().find("32x16"), std::string_view::npos);
  EXPECT_FALSE(EnvProjector::Create(16, 16, 8, WaveletFilter::kHaar).ok());  // not lat-long
  EXPECT_FALSE(EnvProjector::Create(16, 8, 12, WaveletFilter::kHaar).ok());  // N not 2^k
}

}  // namespace
}  // namespace wavebake
