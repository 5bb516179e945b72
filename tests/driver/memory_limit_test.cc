// What a process may use (driver/process/memory_limit.h): cgroup limit files
// as the kernel writes them, a usable size no larger than the machine, and
// the embedded bake's default staging budget within a quarter of it and 4 GiB.
#include "driver/process/memory_limit.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>

#include "driver/bake/embedded_bake.h"

namespace wavebake::driver {
namespace {

TEST(MemoryLimitTest, CgroupLimitFilesParseToBytesOrNoLimit) {
  EXPECT_EQ(ParseCgroupLimit("1073741824\n"), uint64_t{1} << 30);
  // cgroup v1 writes its "unlimited" as a page-rounded INT64_MAX.
  EXPECT_EQ(ParseCgroupLimit("9223372036854771712\n"), uint64_t{9223372036854771712u});
  EXPECT_EQ(ParseCgroupLimit("max\n"), std::nullopt);  // cgroup v2's "unlimited"
  EXPECT_EQ(ParseCgroupLimit(""), std::nullopt);
  EXPECT_EQ(ParseCgroupLimit("12k"), std::nullopt);
  EXPECT_EQ(ParseCgroupLimit("-1"), std::nullopt);
}

TEST(MemoryLimitTest, UsableMemoryIsAtMostThePhysicalMemory) {
  const uint64_t physical =
      uint64_t(::sysconf(_SC_PHYS_PAGES)) * uint64_t(::sysconf(_SC_PAGE_SIZE));
  const uint64_t usable = UsableMemoryBytes();
  EXPECT_GT(usable, 0u);
  EXPECT_LE(usable, physical);
}

TEST(MemoryLimitTest, DefaultStagingBudgetIsAQuarterOfUsableMemoryAtMostFourGiB) {
  const uint64_t budget = EmbeddedBakeOptions::DefaultMemoryStagingBytes();
  EXPECT_GT(budget, 0u);
  EXPECT_LE(budget, UsableMemoryBytes() / 4);
  EXPECT_LE(budget, uint64_t{4} << 30);
  EXPECT_EQ(EmbeddedBakeOptions{}.memory_staging_bytes, budget);
}

}  // namespace
}  // namespace wavebake::driver
