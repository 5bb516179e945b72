// BAKE_TILE's task signals (DESIGN.md §4: a worker whose lease was withdrawn
// stops its task promptly; heartbeats report live progress): a raised cancel
// flag stops the tile before it writes anything, a lowered one changes
// nothing, and the live ray count ends at the tile's own count.
#include <gtest/gtest.h>

#include <atomic>

#include "storage/store/store_layout.h"
#include "tests/worker/staging_testing.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/staging.h"

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
  std::atomic<uint64_t> rays{0};
  const absl::Status s = BakeTile(*ctx, dir.path(), 0, &stats, {&cancel, &rays});
  EXPECT_EQ(s.code(), absl::StatusCode::kCancelled) << s;
  EXPECT_EQ(stats.rays_traced, 0u);
  EXPECT_EQ(stats.bytes_written, 0u);
  EXPECT_EQ(rays, 0u);
  EXPECT_FALSE(std::filesystem::exists(store::Path(dir.path(), store::kStagingTransport) / "0.0"));
  EXPECT_FALSE(std::filesystem::exists(store::Path(dir.path(), store::kStagingTileEnergy) / "0"));
}

TEST(BakeTileCancelTest, LoweredFlagWritesTheSameBytesAsNoSignals) {
  const auto ctx = ContextOrDie("builtin:disk-over-plane", TinyParams());
  ASSERT_NE(ctx, nullptr);
  ScratchDir with_flag, without;
  const std::atomic<bool> cancel{false};
  std::atomic<uint64_t> rays{0};
  TileStats stats;
  ASSERT_TRUE(CreateStaging(ctx->plan, with_flag.path()).ok());
  ASSERT_TRUE(BakeTile(*ctx, with_flag.path(), 0, &stats, {&cancel, &rays}).ok());
  ASSERT_TRUE(CreateStaging(ctx->plan, without.path()).ok());
  ASSERT_TRUE(BakeTile(*ctx, without.path(), 0, nullptr).ok());
  EXPECT_GT(stats.rays_traced, 0u);
  EXPECT_EQ(rays, stats.rays_traced);
  const auto files = FileContents(with_flag.path());
  EXPECT_TRUE(files.contains((std::filesystem::path(store::kStagingTransport) / "0.0").string()));
  EXPECT_EQ(files, FileContents(without.path()));
}

}  // namespace
}  // namespace wavebake
