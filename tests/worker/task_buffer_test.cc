// The per-thread task buffer holds what the last task left: BAKE_TILE and
// TRANSFORM_COLUMNS must write every element they read. Baked once over a
// buffer poisoned with NaN and once over one poisoned with 7, with a padded
// last group, the stores must be the same bytes.
#include "worker/loop/task_buffer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "tests/worker/staging_testing.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

using staging_testing::ContextOrDie;
using staging_testing::FileContents;
using staging_testing::ScratchDir;

void Poison(float value) {
  const std::span<float> buffer = TaskBuffer(size_t{1} << 20);
  std::fill(buffer.begin(), buffer.end(), value);
}

void BakeOverPoison(const BakeContext& ctx, const std::filesystem::path& store, float poison) {
  ASSERT_TRUE(CreateStaging(ctx.plan, store).ok());
  for (int t = 0; t < ctx.plan.tiles(); ++t) {
    Poison(poison);
    ASSERT_TRUE(BakeTile(ctx, store, t, nullptr).ok()) << t;
  }
  for (int g = 0; g < ctx.plan.groups; ++g) {
    Poison(poison);
    ASSERT_TRUE(TransformColumns(ctx, store, g, nullptr).ok()) << g;
  }
}

TEST(TaskBufferTest, TasksWriteEveryElementTheyRead) {
  BakeParams p;
  p.light_res = 8;
  p.supersample = 4;
  p.layout = "camera:16x16";
  p.tile_size = 8;
  p.column_group = 100;  // 384 columns: the last of 4 groups padded
  const auto ctx = ContextOrDie("builtin:cylinder-bump", p);
  ASSERT_NE(ctx, nullptr);
  ASSERT_EQ(ctx->plan.tiles(), 4);
  ScratchDir nan, seven;
  BakeOverPoison(*ctx, nan.path(), std::numeric_limits<float>::quiet_NaN());
  BakeOverPoison(*ctx, seven.path(), 7.0f);
  const auto reference = FileContents(seven.path());
  EXPECT_TRUE(reference.contains("staging/transport/3.3"));
  EXPECT_TRUE(FileContents(nan.path()) == reference);
}

TEST(TaskBufferTest, GrowsKeepsAndReleases) {
  const std::span<float> small = TaskBuffer(10);
  small[0] = 3;
  const std::span<float> same = TaskBuffer(5);
  EXPECT_EQ(same.data(), small.data());  // kept: no smaller allocation
  EXPECT_EQ(same.size(), 5u);
  EXPECT_EQ(same[0], 3);
  EXPECT_EQ(TaskBuffer(1000).size(), 1000u);
  ReleaseTaskBuffer();
  EXPECT_EQ(TaskBuffer(1).size(), 1u);
}

}  // namespace
}  // namespace wavebake
