#include "core/directions/jitter_pattern.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

namespace wavebake {
namespace {

using ::testing::HasSubstr;

JitterPattern MakeOrDie(const Cubemap& cubemap, int supersample, uint64_t seed) {
  absl::StatusOr<JitterPattern> p = MakeJitterPattern(cubemap, supersample, seed);
  EXPECT_TRUE(p.ok()) << p.status();
  return *std::move(p);
}

TEST(JitterPatternTest, SupersamplingRoundsUpToASquare) {
  const Cubemap cubemap(8);
  for (auto [requested, k] : {std::pair{1, 1}, {3, 2}, {4, 2}, {5, 3}, {9, 3}, {10, 4}}) {
    const JitterPattern p = MakeOrDie(cubemap, requested, 1);
    EXPECT_EQ(p.strata, k) << requested;
    EXPECT_EQ(p.per_texel, k * k) << requested;
    EXPECT_EQ(p.x.size(), size_t(cubemap.size()) * k * k);
    EXPECT_EQ(p.corners.size(), size_t(cubemap.size()) * 4);
  }
}

// Each texel's K directions are unit, inside the texel, and one per stratum:
// on a cubemap k times finer, direction (i, j) of texel (x, y) falls in the
// sub-texel (x·k + i, y·k + j).
TEST(JitterPatternTest, DirectionsAreStratifiedInsideTheirTexel) {
  constexpr int kN = 8, kK = 3;
  const Cubemap cubemap(kN), fine(kN * kK);
  const JitterPattern p = MakeOrDie(cubemap, kK * kK, 42);
  for (int m = 0; m < cubemap.size(); ++m) {
    const Texel t = cubemap.TexelOf(m);
    for (int j = 0; j < kK; ++j) {
      for (int i = 0; i < kK; ++i) {
        const Vec3 d = p.Direction(m, j * kK + i);
        ASSERT_NEAR(Length(d), 1, 1e-6f);
        ASSERT_EQ(cubemap.Lookup(d), m);
        ASSERT_EQ(fine.TexelOf(fine.Lookup(d)), (Texel{t.face, t.x * kK + i, t.y * kK + j}))
            << "texel " << m << " stratum " << i << "," << j;
      }
    }
  }
}

TEST(JitterPatternTest, CornersBoundTheTexelAndSolidAnglesCoverTheSphere) {
  const Cubemap cubemap(8);
  const JitterPattern p = MakeOrDie(cubemap, 4, 1);
  double total = 0;
  for (int m = 0; m < cubemap.size(); ++m) {
    Vec3 sum;
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(Length(p.corners[m * 4 + c]), 1, 1e-6f);
      sum = sum + p.corners[m * 4 + c];
    }
    EXPECT_EQ(cubemap.Lookup(sum), m);  // the corners' mean direction lies inside
    total += p.solid_angle[m];
  }
  EXPECT_NEAR(total, 4 * std::numbers::pi, 1e-4);
}

TEST(JitterPatternTest, SeedAloneDecidesThePattern) {
  const Cubemap cubemap(16);
  const JitterPattern a = MakeOrDie(cubemap, 4, 1234), b = MakeOrDie(cubemap, 4, 1234);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
  const JitterPattern c = MakeOrDie(cubemap, 4, 1235);
  size_t differ = 0;
  for (size_t i = 0; i < a.x.size(); ++i) differ += a.x[i] != c.x[i] || a.y[i] != c.y[i];
  EXPECT_GT(differ, a.x.size() * 99 / 100);
}

// Jitter is not a fixed offset: within one pattern the positions of the
// samples inside their strata vary from texel to texel.
TEST(JitterPatternTest, JitterVariesAcrossTexels) {
  const Cubemap cubemap(8), fine(8 * 64);
  const JitterPattern p = MakeOrDie(cubemap, 1, 9);
  std::set<int> offsets;  // position inside the texel on a 64×64 sub-grid
  for (int m = 0; m < cubemap.size(); ++m) {
    const Texel t = cubemap.TexelOf(m), f = fine.TexelOf(fine.Lookup(p.Direction(m, 0)));
    offsets.insert((f.y - t.y * 64) * 64 + (f.x - t.x * 64));
  }
  EXPECT_GT(offsets.size(), size_t(cubemap.size()) * 9 / 10);
}

TEST(JitterPatternTest, RejectsBadSupersampling) {
  const Cubemap cubemap(8);
  EXPECT_THAT(MakeJitterPattern(cubemap, 0, 1).status().message(), HasSubstr("supersample 0"));
  EXPECT_THAT(MakeJitterPattern(cubemap, 257, 1).status().message(), HasSubstr("supersample 257"));
}

}  // namespace
}  // namespace wavebake
