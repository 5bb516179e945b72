// BAKE_TILE as a task: bit-identical staging whatever the threads, the tile
// order and retries (DESIGN.md §1 "Determinism"), its counters, and bad input.
#include "worker/tiles/bake_tile.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <numeric>
#include <random>
#include <thread>
#include <vector>

#include "core/transport/refined_row.h"
#include "core/transport/transport_row.h"
#include "storage/store/store_layout.h"
#include "tests/worker/staging_testing.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

using staging_testing::ContextOrDie;
using staging_testing::FileContents;
using staging_testing::ScratchDir;
using ::testing::HasSubstr;

// cylinder-bump: shadows and a curved ground, 16 tiles of 4×4 (or 4 of 8×8)
// and 4 groups (the last padded), so chunk boundaries are everywhere.
BakeParams SmallParams(int tile_size = 4) {
  BakeParams p;
  p.light_res = 8;
  p.supersample = 4;
  p.layout = "camera:16x16";
  p.tile_size = tile_size;
  p.column_group = 100;
  return p;
}

void BakeInOrder(const BakeContext& ctx, const std::filesystem::path& store,
                 const std::vector<int>& order) {
  ASSERT_TRUE(CreateStaging(ctx.plan, store).ok());
  for (int t : order) ASSERT_TRUE(BakeTile(ctx, store, t, nullptr).ok()) << t;
}

void BakeOnThreads(const BakeContext& ctx, const std::filesystem::path& store, int threads) {
  ASSERT_TRUE(CreateStaging(ctx.plan, store).ok());
  std::atomic<int> next{0};
  std::vector<absl::Status> results(ctx.plan.tiles());
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) {
    pool.emplace_back([&] {
      for (int t = next++; t < ctx.plan.tiles(); t = next++) {
        results[t] = BakeTile(ctx, store, t, nullptr);
      }
    });
  }
  for (std::thread& t : pool) t.join();
  for (const absl::Status& s : results) EXPECT_TRUE(s.ok()) << s;
}

// Each run writes its own store; the second context stands for another
// worker deriving the job on its own. (8×8 tiles: the chunk files, not the
// rays, are what costs time here.)
TEST(BakeTileTest, StagingIsBitIdenticalAcrossThreadsOrderAndRetries) {
  const auto ctx = ContextOrDie("builtin:cylinder-bump", SmallParams(8));
  const auto other_worker = ContextOrDie("builtin:cylinder-bump", SmallParams(8));
  ASSERT_NE(ctx, nullptr);
  ASSERT_NE(other_worker, nullptr);
  const int tiles = ctx->plan.tiles();
  ASSERT_EQ(tiles, 4);
  ASSERT_EQ(ctx->plan.groups, 4);

  std::vector<int> in_order(tiles);
  std::iota(in_order.begin(), in_order.end(), 0);
  std::vector<int> shuffled_with_retries = in_order;
  std::shuffle(shuffled_with_retries.begin(), shuffled_with_retries.end(), std::mt19937(5));
  shuffled_with_retries.push_back(shuffled_with_retries.front());  // a retried task
  shuffled_with_retries.push_back(2);

  ScratchDir one, two, shuffled;
  BakeInOrder(*ctx, one.path(), in_order);
  BakeOnThreads(*other_worker, two.path(), 2);
  BakeInOrder(*ctx, shuffled.path(), shuffled_with_retries);

  const auto reference = FileContents(one.path());
  // .zgroup ×2, .zarray ×2, groups × tiles transport chunks, tiles energies.
  EXPECT_EQ(reference.size(), size_t(4 + ctx->plan.groups * tiles + tiles));
  EXPECT_TRUE(reference.contains("staging/transport/3.3"));
  EXPECT_TRUE(FileContents(two.path()) == reference) << "1 vs 2 threads";
  EXPECT_TRUE(FileContents(shuffled.path()) == reference) << "shuffled order with retries";
}

// rays_traced is what the row tracer (refined or brute force) reports for the
// tile's samples, samples counts the non-masked cells, bytes_written the
// chunk files on disk.
TEST(BakeTileTest, StatsCountRaysSamplesAndBytes) {
  for (bool refine : {true, false}) {
    BakeParams params = SmallParams();
    params.refine = refine;
    const auto ctx = ContextOrDie("builtin:cylinder-bump", params);
    ASSERT_NE(ctx, nullptr);
    const JobPlan& plan = ctx->plan;
    ScratchDir dir;
    ASSERT_TRUE(CreateStaging(plan, dir.path()).ok());
    uint64_t all_samples = 0;
    for (int t : {0, 9, 14}) {  // tile 0 is a corner of sky: all masked
      TileStats stats;
      ASSERT_TRUE(BakeTile(*ctx, dir.path(), t, &stats).ok());

      TransportStats traced;
      uint64_t samples = 0;
      std::vector<float> row(plan.columns);
      const TileRect r = plan.Tile(t);
      for (int y = r.y0; y < r.y0 + r.height; ++y) {
        for (int x = r.x0; x < r.x0 + r.width; ++x) {
          const int32_t id = ctx->samples.grid[y * plan.width + x];
          if (id < 0) continue;
          ++samples;
          RefineScratch scratch;
          if (refine) {
            RefinedTransportRow(ctx->caster, ctx->cubemap, ctx->jitter, *ctx->refine,
                                ctx->samples.position[id], ctx->samples.normal[id], ctx->epsilon,
                                row, &traced, scratch);
          } else {
            TransportRow(ctx->caster, ctx->cubemap, ctx->jitter, ctx->samples.position[id],
                         ctx->samples.normal[id], ctx->epsilon, row, &traced);
          }
        }
      }
      uint64_t bytes =
          std::filesystem::file_size(dir.path() / "staging/tile_energy" / std::to_string(t));
      for (int g = 0; g < plan.groups; ++g) {
        bytes += std::filesystem::file_size(dir.path() / "staging/transport" /
                                            (std::to_string(g) + "." + std::to_string(t)));
      }
      EXPECT_EQ(stats.samples, samples) << t;
      EXPECT_EQ(stats.rays_traced, traced.rays_traced) << t;
      EXPECT_EQ(stats.bytes_written, bytes) << t;
      all_samples += samples;
    }
    EXPECT_GT(all_samples, 0u);
  }
}

TEST(BakeTileTest, TileOutOfRangeIsInvalidArgumentAndWritesNothing) {
  const auto ctx = ContextOrDie("builtin:cylinder-bump", SmallParams());
  ASSERT_NE(ctx, nullptr);
  ScratchDir dir;
  ASSERT_TRUE(CreateStaging(ctx->plan, dir.path()).ok());
  const auto before = FileContents(dir.path());
  for (int t : {-1, ctx->plan.tiles(), 1 << 30}) {
    TileStats stats;
    const absl::Status s = BakeTile(*ctx, dir.path(), t, &stats);
    EXPECT_TRUE(absl::IsInvalidArgument(s)) << s;
    EXPECT_THAT(s.message(), HasSubstr("tile"));
    EXPECT_EQ(stats.rays_traced, 0u);
  }
  EXPECT_TRUE(FileContents(dir.path()) == before);
}

TEST(BakeTileTest, NeedsStagingOfTheSamePlan) {
  const auto ctx = ContextOrDie("builtin:cylinder-bump", SmallParams());
  ASSERT_NE(ctx, nullptr);
  ScratchDir dir;
  const std::filesystem::path store = dir.path() / "out.wbk";
  EXPECT_TRUE(absl::IsNotFound(BakeTile(*ctx, store, 0, nullptr)));
  EXPECT_FALSE(std::filesystem::exists(store));

  JobPlan other = ctx->plan;
  other.group_size = 128;
  other.groups = 3;
  ASSERT_TRUE(CreateStaging(other, store).ok());
  const absl::Status s = BakeTile(*ctx, store, 0, nullptr);
  EXPECT_TRUE(absl::IsFailedPrecondition(s)) << s;
  EXPECT_THAT(s.message(), HasSubstr("staging/transport"));
}

// Bad jobs fail in MakeBakeContext, before any store exists (DESIGN.md §4:
// the message names the field or file; nothing half-written).
TEST(BakeTileTest, BadJobsFailBeforeAnythingIsWritten) {
  ScratchDir dir;
  {
    std::ofstream(dir.path() / "quad.obj") << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"
                                              "f 1 4 3\nf 1 3 2\n";
    std::ofstream(dir.path() / "no_camera.json") << R"({"meshes": [{"file": "quad.obj"}]})";
  }
  const auto before = FileContents(dir.path());

  BakeParams p = SmallParams();
  p.light_res = 12;
  absl::StatusOr<std::unique_ptr<BakeContext>> ctx = MakeBakeContext("builtin:furnace", p);
  EXPECT_TRUE(absl::IsInvalidArgument(ctx.status())) << ctx.status();
  EXPECT_THAT(ctx.status().message(), HasSubstr("light_res"));

  const std::string no_camera = (dir.path() / "no_camera.json").string();
  ctx = MakeBakeContext(no_camera, SmallParams());
  EXPECT_FALSE(ctx.ok());
  EXPECT_THAT(ctx.status().message(), HasSubstr("camera"));
  p = SmallParams();
  p.layout = "hilbert:4x4";  // the same file bakes with a mesh layout
  EXPECT_TRUE(MakeBakeContext(no_camera, p).ok());

  const std::string missing = (dir.path() / "missing.obj").string();
  ctx = MakeBakeContext(missing, SmallParams());
  EXPECT_FALSE(ctx.ok());
  EXPECT_THAT(ctx.status().message(), HasSubstr("missing.obj"));

  EXPECT_TRUE(FileContents(dir.path()) == before);
}

}  // namespace
}  // namespace wavebake
