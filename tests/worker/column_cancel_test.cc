// Cancel inside the column stage (DESIGN.md §4 Cancel): TRANSFORM_COLUMNS and
// FINALIZE stop at their cancel flag without writing their result (no group
// file, no manifest), and a task that was stopped and run again writes the
// same bytes as one that never was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>

#include "storage/store/store_layout.h"
#include "tests/worker/column_test_support.h"
#include "worker/columns/finalize.h"
#include "worker/columns/group_result.h"
#include "worker/columns/transform_columns.h"

namespace wavebake {
namespace {

using column_testing::MakeContext;
using column_testing::ReadTree;
using column_testing::ScratchDir;
using column_testing::SyntheticMatrix;
using column_testing::TransformAll;
using column_testing::WriteSyntheticStaging;

BakeParams SmallJob() {
  BakeParams p;
  p.light_res = 8;
  p.column_group = 100;
  return p;
}

TEST(ColumnCancelTest, TransformColumnsStopsAndWritesNothing) {
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(SmallJob());
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(32, 32));
  std::atomic<bool> cancel{true};
  GroupStats stats;
  const absl::Status s = TransformColumns(*ctx, store, 1, &stats, {&cancel});
  EXPECT_EQ(s.code(), absl::StatusCode::kCancelled) << s;
  EXPECT_FALSE(std::filesystem::exists(GroupResultPath(store, 1)));
  cancel = false;
  ASSERT_TRUE(TransformColumns(*ctx, store, 1, &stats, {&cancel}).ok());
  EXPECT_TRUE(std::filesystem::exists(GroupResultPath(store, 1)));
}

TEST(ColumnCancelTest, FinalizeStopsBeforeTheManifestAndItsRetryMatches) {
  ScratchDir dir;
  auto ctx = MakeContext(SmallJob());
  const auto plain = dir.path() / "plain.wbk", stopped = dir.path() / "stopped.wbk";
  for (const auto& store : {plain, stopped}) {
    WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(32, 32));
    TransformAll(*ctx, store);
  }
  ASSERT_TRUE(Finalize(*ctx, plain, {}).ok());
  std::atomic<bool> cancel{true};
  const absl::Status s = Finalize(*ctx, stopped, {.cancel = &cancel});
  EXPECT_EQ(s.code(), absl::StatusCode::kCancelled) << s;
  EXPECT_FALSE(std::filesystem::exists(stopped / ".zattrs"));
  EXPECT_TRUE(std::filesystem::exists(store::Path(stopped, store::kStaging)));
  ASSERT_TRUE(Finalize(*ctx, stopped, {}).ok());  // a later lease of the same task
  EXPECT_EQ(ReadTree(stopped), ReadTree(plain));
}

}  // namespace
}  // namespace wavebake
