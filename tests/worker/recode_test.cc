// Column-stage-only reruns on a kept trace (worker/tiles/recode.h): the recoded
// store is bit-identical to a fresh bake with the new column parameters, the
// trace is left untouched, and a trace of other trace parameters is refused
// by name.
#include "worker/tiles/recode.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>

#include "tests/testing/file_tree.h"
#include "tests/worker/staging_testing.h"
#include "worker/columns/finalize.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

using staging_testing::ContextOrDie;
using test_support::ReadTree;
using test_support::ScratchDir;
using ::testing::HasSubstr;

BakeParams Traced() {
  BakeParams p;
  p.light_res = 8;
  p.layout = "camera:16x16";
  p.tile_size = 8;
  p.column_group = 100;
  return p;
}

// The three tasks by hand, as a worker runs them.
void BakeByHand(const BakeContext& ctx, const std::filesystem::path& store, bool keep_staging) {
  ASSERT_TRUE(CreateStaging(ctx.plan, store, TraceRecord(ctx)).ok());
  for (int t = 0; t < ctx.plan.tiles(); ++t) ASSERT_TRUE(BakeTile(ctx, store, t, nullptr).ok());
  for (int g = 0; g < ctx.plan.groups; ++g)
    ASSERT_TRUE(TransformColumns(ctx, store, g, nullptr).ok());
  ASSERT_TRUE(Finalize(ctx, store, {.keep_staging = keep_staging}).ok());
}

TEST(RecodeTest, RecodedStoreIsTheFreshBakeOfTheNewColumnParameters) {
  ScratchDir dir;
  const auto traced = ContextOrDie("builtin:cylinder-bump", Traced());
  ASSERT_NE(traced, nullptr);
  BakeByHand(*traced, dir.path() / "traced.wbk", true);
  const auto before = ReadTree(dir.path() / "traced.wbk");

  BakeParams p = Traced();
  p.target_error = 0.04;
  p.column_mode = ColumnMode::k2d;
  p.bits = 10;
  const auto ctx = ContextOrDie("builtin:cylinder-bump", p);
  ASSERT_NE(ctx, nullptr);
  ASSERT_TRUE(
      Recode(*ctx, dir.path() / "traced.wbk", dir.path() / "recoded.wbk", {.threads = 2}).ok());
  BakeByHand(*ctx, dir.path() / "fresh.wbk", false);
  const auto recoded = ReadTree(dir.path() / "recoded.wbk");
  ASSERT_TRUE(recoded.contains("transport/indptr/0"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "recoded.wbk/staging"));
  EXPECT_TRUE(recoded == ReadTree(dir.path() / "fresh.wbk"));
  EXPECT_TRUE(ReadTree(dir.path() / "traced.wbk") == before);
  // Only the three stores: no partial directory is left.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 3);
}

// The trace alone (TraceStaging), then the column stage (Recode): the store
// of the three tasks by hand. Cancelled before it starts, it leaves nothing.
TEST(RecodeTest, TraceThenRecodeIsTheBake) {
  ScratchDir dir;
  const auto ctx = ContextOrDie("builtin:cylinder-bump", Traced());
  ASSERT_NE(ctx, nullptr);
  int last_tiles = 0;
  absl::StatusOr<uint64_t> rays =
      TraceStaging(*ctx, dir.path() / "trace", {.threads = 2, .on_tile = [&](int tiles, uint64_t) {
                                                  EXPECT_EQ(tiles, last_tiles + 1);
                                                  last_tiles = tiles;
                                                }});
  ASSERT_TRUE(rays.ok()) << rays.status();
  EXPECT_GT(*rays, 0u);
  EXPECT_EQ(last_tiles, ctx->plan.tiles());
  EXPECT_EQ(TraceStaging(*ctx, dir.path() / "trace").status().code(),
            absl::StatusCode::kAlreadyExists);
  ASSERT_TRUE(Recode(*ctx, dir.path() / "trace", dir.path() / "recoded.wbk").ok());
  BakeByHand(*ctx, dir.path() / "fresh.wbk", false);
  EXPECT_TRUE(ReadTree(dir.path() / "recoded.wbk") == ReadTree(dir.path() / "fresh.wbk"));

  const std::atomic<bool> cancel{true};
  EXPECT_EQ(TraceStaging(*ctx, dir.path() / "cancelled", {.cancel = &cancel}).status().code(),
            absl::StatusCode::kCancelled);
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 3);  // trace, recoded.wbk, fresh.wbk
}

TEST(RecodeTest, OtherTraceParametersAreRefusedByName) {
  ScratchDir dir;
  const auto traced = ContextOrDie("builtin:cylinder-bump", Traced());
  ASSERT_NE(traced, nullptr);
  BakeByHand(*traced, dir.path() / "traced.wbk", true);
  for (auto [edit, field] : std::initializer_list<std::pair<void (*)(BakeParams&), const char*>>{
           {[](BakeParams& p) { p.seed = 2; }, "seed"},
           {[](BakeParams& p) { p.supersample = 9; }, "supersample"},
           {[](BakeParams& p) { p.refine = false; }, "refine"},
           {[](BakeParams& p) { p.light_res = 16; }, "light_res"}}) {
    BakeParams p = Traced();
    edit(p);
    const auto ctx = ContextOrDie("builtin:cylinder-bump", p);
    ASSERT_NE(ctx, nullptr);
    const auto out = dir.path() / "out.wbk";
    const absl::Status s = Recode(*ctx, dir.path() / "traced.wbk", out);
    EXPECT_EQ(s.code(), absl::StatusCode::kFailedPrecondition) << field;
    EXPECT_THAT(std::string(s.message()), HasSubstr(field));
    EXPECT_FALSE(std::filesystem::exists(out)) << field;
  }
  const auto ctx = ContextOrDie("builtin:sphere-plane", Traced());  // another scene
  EXPECT_THAT(std::string(Recode(*ctx, dir.path() / "traced.wbk", dir.path() / "o.wbk").message()),
              HasSubstr("scene_hash"));
  // A finished store without its staging, and an existing output.
  BakeByHand(*traced, dir.path() / "plain.wbk", false);
  EXPECT_EQ(Recode(*traced, dir.path() / "plain.wbk", dir.path() / "o.wbk").code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(Recode(*traced, dir.path() / "traced.wbk", dir.path() / "plain.wbk").code(),
            absl::StatusCode::kAlreadyExists);
}

}  // namespace
}  // namespace wavebake
