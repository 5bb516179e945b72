#include "core/bake/job_plan.h"

#include <gtest/gtest.h>

namespace wavebake {
namespace {

// The plan's own group size: a power of two up to 1024 whose column images
// (group × cells float32) fit in 256 MiB, never more than the columns.
TEST(AutoGroupSizeTest, LargestPowerOfTwoWhoseImagesFit) {
  EXPECT_EQ(AutoGroupSize(24576, 64 * 64), 1024);    // 16 MiB of images: the cap
  EXPECT_EQ(AutoGroupSize(24576, 256 * 256), 1024);  // exactly 256 MiB
  EXPECT_EQ(AutoGroupSize(98304, 512 * 512), 256);   // 1024 would be 1 GiB
  EXPECT_EQ(AutoGroupSize(98304, 1024 * 1024), 64);
  EXPECT_EQ(AutoGroupSize(384, 64 * 64), 384);  // fewer columns than the cap
  EXPECT_EQ(AutoGroupSize(6144, 1 << 28), 1);   // at least one column
}

TEST(AutoGroupSizeTest, AGivenGroupSizeIsKept) {
  BakeParams p;
  p.light_res = 16;  // 1536 columns
  p.column_group = 100;
  EXPECT_EQ(MakeJobPlan(p, 64, 64).group_size, 100);
  EXPECT_EQ(MakeJobPlan(p, 64, 64).groups, 16);
  p.column_group = 0;
  EXPECT_EQ(MakeJobPlan(p, 64, 64).group_size, 1024);
  EXPECT_EQ(MakeJobPlan(p, 64, 64).groups, 2);
}

}  // namespace
}  // namespace wavebake
