// BAKE_TILE's cancellation hook (DESIGN.md §4: a worker whose lease was
// withdrawn stops its task promptly): a raised flag stops the tile before it
// writes anything, a lowered one changes nothing.
#include <gtest/gtest.h>

#include <atomic>

#include "storage/store_layout.h"
#include "tests/worker/staging_testing.h"
#include "worker/bake_tile.h"
#include "worker/staging.h"

namespace wavebake {
namespace {

using staging_testing::ContextOrDie;
using staging_testing::FileContents;
using staging_testing::ScratchDir;

BakeParams TinyParams() {
  BakeParams p;
  p.light_res = 8;
  p.layout = "camera:8x8";
  p.tile_size = 8;
  return p;
}

TEST(BakeTileCancelTest, RaisedFlagStopsBeforeAnyChunkIsWritten) {
  const auto ctx = ContextOrDie("builtin:disk-over-plane", TinyParams());
  ASSERT_NE(ctx, nullptr);
  ScratchDir dir;
  ASSERT_TRUE(CreateStaging(ctx->plan, dir.path()).ok());
  const std::atomic<bool> cancel{true};
  TileStats stats;
  const absl::Status s = BakeTile(*ctx, dir.path(), 0, &stats, &cancel);
  EXPECT_EQ(s.code(), absl::StatusCode::kCancelled) << s;
  EXPECT_EQ(stats.rays_traced, 0u);
  EXPECT_EQ(stats.bytes_written, 0u);
  EXPECT_FALSE(std::filesystem::exists(store::Path(dir.path(), store::kStagingTransport) / "0.0"));
  EXPECT_FALSE(std::filesystem::exists(store::Path(dir.path(), store::kStagingTileEnergy) / "0"));
}

TEST(BakeTileCancelTest, LoweredFlagWritesTheSameBytesAsNoFlag) {
  const auto ctx = ContextOrDie("builtin:disk-over-plane", TinyParams());
  ASSERT_NE(ctx, nullptr);
  ScratchDir with_flag, without;
  const std::atomic<bool> cancel{false};
  for (const auto* dir : {&with_flag, &without}) {
    ASSERT_TRUE(CreateStaging(ctx->plan, dir->path()).ok());
    ASSERT_TRUE(BakeTile(*ctx, dir->path(), 0, nullptr, dir == &with_flag ? &cancel : nullptr).ok());
  }
  const auto files = FileContents(with_flag.path());
  EXPECT_TRUE(files.contains((std::filesystem::path(store::kStagingTransport) / "0.0").string()));
  EXPECT_EQ(files, FileContents(without.path()));
}

}  // namespace
}  // namespace wavebake
