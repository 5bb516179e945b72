#include "core/util/power_of_two.h"

#include <gtest/gtest.h>

#include <limits>

namespace wavebake {
namespace {

TEST(PowerOfTwo, ZeroNegativesAndNonPowersAreNot) {
  for (int v : {0, -1, -2, -4096, std::numeric_limits<int>::min(), 3, 6, 12, 4095, 4097})
    EXPECT_FALSE(IsPowerOfTwo(v)) << v;
}

TEST(PowerOfTwo, EveryPowerOfAnIntIs) {
  for (int b = 0; b < 31; ++b) EXPECT_TRUE(IsPowerOfTwo(1 << b)) << b;
}

TEST(PowerOfTwo, TheRangeIncludesBothEnds) {
  EXPECT_TRUE(IsPowerOfTwoIn(8, 8, 256));
  EXPECT_TRUE(IsPowerOfTwoIn(256, 8, 256));
  EXPECT_FALSE(IsPowerOfTwoIn(4, 8, 256));
  EXPECT_FALSE(IsPowerOfTwoIn(512, 8, 256));
  EXPECT_FALSE(IsPowerOfTwoIn(0, 0, 256));  // 0 is in range but no power of two
  EXPECT_FALSE(IsPowerOfTwoIn(24, 8, 256));
}

}  // namespace
}  // namespace wavebake
