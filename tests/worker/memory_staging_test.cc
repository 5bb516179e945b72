// Staging held in memory (worker/tiles/memory_staging.h) is the transpose of
// DESIGN.md §2 without the store's round trip: the store it produces is
// byte for byte the store-staged one's, whichever tiles went to memory, in
// any order and with retries; a job that does not fit the budget goes
// through the store; a chunk found in neither place fails the group instead
// of reading as zeros; FINALIZE lets the memory go.
#include "worker/tiles/memory_staging.h"

#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <random>

#include "storage/store/store_layout.h"
#include "tests/testing/file_tree.h"
#include "tests/testing/scratch_dir.h"
#include "worker/columns/finalize.h"
#include "worker/columns/group_result.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

using test_support::ReadTree;
using test_support::ScratchDir;

constexpr char kMemoryScene[] = "builtin:cylinder-bump";

// 16×16 camera samples in 4 tiles, N = 8: 384 columns in 4 groups.
BakeParams MemoryJob() {
  BakeParams p;
  p.light_res = 8;
  p.layout = "camera:16x16";
  p.tile_size = 8;
  p.column_group = 100;
  return p;
}

std::unique_ptr<BakeContext> MemoryJobContext() {
  absl::StatusOr<std::unique_ptr<BakeContext>> ctx = MakeBakeContext(kMemoryScene, MemoryJob());
  EXPECT_TRUE(ctx.ok()) << ctx.status();
  return ctx.ok() ? *std::move(ctx) : nullptr;
}

uint64_t RawStagingBytes(const JobPlan& plan) {
  return uint64_t(plan.groups) * plan.all_tiles() * plan.group_size * plan.tile_cells() * 4;
}

// The tasks by hand; tiles listed in `in_memory` stage through `memory`.
absl::Status BakeByHandWithMemory(const BakeContext& ctx, const std::filesystem::path& store,
                                  MemoryStaging* memory, const std::vector<int>& tiles,
                                  const std::vector<bool>& in_memory,
                                  const std::vector<int>& groups) {
  if (absl::Status s = CreateStaging(ctx.plan, store); !s.ok()) return s;
  for (size_t i = 0; i < tiles.size(); ++i)
    if (absl::Status s =
            BakeTile(ctx, store, tiles[i], nullptr, {}, in_memory[tiles[i]] ? memory : nullptr);
        !s.ok())
      return s;
  for (int g : groups)
    if (absl::Status s = TransformColumns(ctx, store, g, nullptr, {}, memory); !s.ok()) return s;
  return Finalize(ctx, store, {.memory = memory});
}

TEST(MemoryStagingTest, StoreIsTheStoreStagedOneWhateverWentToMemory) {
  const std::unique_ptr<BakeContext> ctx = MemoryJobContext();
  ASSERT_NE(ctx, nullptr);
  const JobPlan& plan = ctx->plan;
  ASSERT_EQ(plan.tiles(), 4);
  ASSERT_EQ(plan.groups, 4);
  ScratchDir dir;
  std::vector<int> tiles(plan.tiles()), groups(plan.groups);
  std::iota(tiles.begin(), tiles.end(), 0);
  std::iota(groups.begin(), groups.end(), 0);
  const std::vector<bool> none(plan.tiles(), false);
  ASSERT_TRUE(
      BakeByHandWithMemory(*ctx, dir.path() / "disk.wbk", nullptr, tiles, none, groups).ok());
  const auto expected = ReadTree(dir.path() / "disk.wbk");
  ASSERT_TRUE(expected.contains("transport/indptr/0"));

  // Every tile in memory, shuffled, a tile and a group retried.
  std::mt19937 rng(11);
  std::shuffle(tiles.begin(), tiles.end(), rng);
  std::shuffle(groups.begin(), groups.end(), rng);
  tiles.push_back(tiles.front());
  groups.push_back(groups.front());
  MemoryStaging memory(2 * RawStagingBytes(plan));  // the group results held too
  const std::vector<bool> all(plan.tiles(), true);
  const auto held = dir.path() / "memory.wbk";
  ASSERT_TRUE(BakeByHandWithMemory(*ctx, held, &memory, tiles, all, groups).ok());
  EXPECT_TRUE(ReadTree(held) == expected);
  EXPECT_EQ(memory.held_bytes(), 0u);  // FINALIZE dropped the job

  // Half the tiles in memory, half in the store.
  const std::vector<bool> half = {true, false, true, false};
  const auto mixed = dir.path() / "mixed.wbk";
  ASSERT_TRUE(BakeByHandWithMemory(*ctx, mixed, &memory, tiles, half, groups).ok());
  EXPECT_TRUE(ReadTree(mixed) == expected);
}

// The bunny's 2503 vertices along a Hilbert curve of 64×64 cells leave its
// last 32×32 tile without a sample: in memory that tile is never traced and
// its chunks are pages never written, which read as the zeros the store
// holds for it.
TEST(MemoryStagingTest, ATileWithoutSamplesStagesTheSameZeros) {
  BakeParams p;
  p.light_res = 8;
  p.layout = "hilbert:64x64";
  p.tile_size = 32;
  absl::StatusOr<std::unique_ptr<BakeContext>> made =
      MakeBakeContext(std::string(WB_SHARED_DATA) + "/models/bunny.obj", p);
  ASSERT_TRUE(made.ok()) << made.status();
  const BakeContext& ctx = **made;
  const JobPlan& plan = ctx.plan;
  ASSERT_EQ(plan.tiles(), 4);
  int empty_tiles = 0;
  for (int t = 0; t < plan.tiles(); ++t) {
    const TileRect r = plan.Tile(t);
    bool any = false;
    for (int y = r.y0; y < r.y0 + r.height; ++y)
      for (int x = r.x0; x < r.x0 + r.width; ++x) any |= ctx.samples.grid[y * 64 + x] >= 0;
    empty_tiles += !any;
  }
  ASSERT_EQ(empty_tiles, 1);
  ScratchDir dir;
  std::vector<int> tiles(plan.tiles()), groups(plan.groups);
  std::iota(tiles.begin(), tiles.end(), 0);
  std::iota(groups.begin(), groups.end(), 0);
  const auto disk = dir.path() / "disk.wbk", held = dir.path() / "memory.wbk";
  ASSERT_TRUE(BakeByHandWithMemory(ctx, disk, nullptr, tiles,
                                   std::vector<bool>(plan.tiles(), false), groups)
                  .ok());
  MemoryStaging memory(RawStagingBytes(plan));
  ASSERT_TRUE(
      BakeByHandWithMemory(ctx, held, &memory, tiles, std::vector<bool>(plan.tiles(), true), groups)
          .ok());
  EXPECT_TRUE(ReadTree(held) == ReadTree(disk));
}

// The tasks of a job with auxiliary tiles by hand, every tile into memory
// (each cancelled once first if `cancel_first`): nothing of the auxiliary
// rows reaches the store's staging, and the store is the store-staged one's.
void ExpectAuxJobInMemoryIsTheStoreStaged(const BakeContext& ctx, bool cancel_first) {
  const JobPlan& plan = ctx.plan;
  ASSERT_GT(plan.aux_tiles(), 0);
  ScratchDir dir;
  std::vector<int> tiles(plan.all_tiles()), groups(plan.groups);
  std::iota(tiles.begin(), tiles.end(), 0);
  std::iota(groups.begin(), groups.end(), 0);
  const auto disk = dir.path() / "disk.wbk", held = dir.path() / "memory.wbk";
  ASSERT_TRUE(BakeByHandWithMemory(ctx, disk, nullptr, tiles,
                                   std::vector<bool>(plan.all_tiles(), false), groups)
                  .ok());
  MemoryStaging memory(RawStagingBytes(plan));
  ASSERT_TRUE(CreateStaging(plan, held).ok());
  const std::atomic<bool> cancel{true};
  for (int t = 0; cancel_first && t < plan.all_tiles(); ++t)
    EXPECT_TRUE(absl::IsCancelled(BakeTile(ctx, held, t, nullptr, {.cancel = &cancel}, &memory)));
  for (int t : tiles) ASSERT_TRUE(BakeTile(ctx, held, t, nullptr, {}, &memory).ok());
  EXPECT_FALSE(std::filesystem::exists(held / store::kStagingAuxTransport / "0.0"));
  for (int g : groups) ASSERT_TRUE(TransformColumns(ctx, held, g, nullptr, {}, &memory).ok());
  ASSERT_TRUE(Finalize(ctx, held, {.memory = &memory}).ok());
  EXPECT_TRUE(ReadTree(held) == ReadTree(disk));
}

// A camera's bounces gather from its auxiliary vertices, whose direct rows
// are tiles of their own (core/bake/bake_gather.h): they go to memory too,
// and the store is still the store-staged one's; nothing of them is in the
// store's staging.
TEST(MemoryStagingTest, AuxiliaryRowsOfBouncesStageInMemoryToo) {
  BakeParams p = MemoryJob();
  p.bounces = 2;
  p.gather_rays = 16;
  absl::StatusOr<std::unique_ptr<BakeContext>> made = MakeBakeContext(kMemoryScene, p);
  ASSERT_TRUE(made.ok()) << made.status();
  ExpectAuxJobInMemoryIsTheStoreStaged(**made, false);
}

// Into memory a tile is traced a band of rows at a time (about 4 MiB of
// rows), each band transposed straight into the job's chunks. A 64×64 tile
// at N = 8 (4096 rows of 400 floats, 6.5 MB) takes two bands, the second
// partial, and so do its auxiliary tiles; a tile cancelled before its first
// band gives back the chunks it began, and its retry fills them. The store
// is the store-staged one's.
TEST(MemoryStagingTest, TilesLargerThanABandStageBandByBandTheSameBytes) {
  BakeParams p = MemoryJob();
  p.layout = "camera:64x64";
  p.tile_size = 64;
  p.bounces = 1;
  p.gather_rays = 8;
  absl::StatusOr<std::unique_ptr<BakeContext>> made = MakeBakeContext(kMemoryScene, p);
  ASSERT_TRUE(made.ok()) << made.status();
  const JobPlan& plan = (*made)->plan;
  ASSERT_EQ(plan.tiles(), 1);
  ASSERT_GT(size_t(plan.tile_cells()) * (plan.columns + 16) * sizeof(float), size_t{4} << 20);
  ExpectAuxJobInMemoryIsTheStoreStaged(**made, true);
}

TEST(MemoryStagingTest, MemoryChunksAreNotInTheStoreAndAJobOverBudgetUsesTheStore) {
  const std::unique_ptr<BakeContext> ctx = MemoryJobContext();
  ASSERT_NE(ctx, nullptr);
  const JobPlan& plan = ctx->plan;
  ScratchDir dir;
  const auto fits = dir.path() / "fits.wbk", over = dir.path() / "over.wbk";
  MemoryStaging memory(RawStagingBytes(plan));
  for (const auto& store : {fits, over}) {
    ASSERT_TRUE(CreateStaging(plan, store).ok());
    ASSERT_TRUE(BakeTile(*ctx, store, 0, nullptr, {}, &memory).ok());
  }
  // The first job took the whole budget: the second is staged in the store.
  EXPECT_NE(memory.Find(fits), nullptr);
  EXPECT_EQ(memory.Find(over), nullptr);
  EXPECT_EQ(memory.held_bytes(), RawStagingBytes(plan));
  const std::filesystem::path chunk = std::filesystem::path(store::kStagingTransport) / "0.0";
  EXPECT_FALSE(std::filesystem::exists(fits / chunk));
  EXPECT_TRUE(std::filesystem::exists(over / chunk));
  EXPECT_TRUE(std::filesystem::exists(fits / store::kStagingTileEnergy / "0"));
  memory.Drop(fits);
  EXPECT_EQ(memory.held_bytes(), 0u);
}

// TRANSFORM_COLUMNS leaves its group results in the job's memory, not in
// staging/groups, and FINALIZE finds them there (the tests below with a
// budget of the chunks alone have them go to the files, and the stores are
// the same); a job staged in the store writes the files.
TEST(MemoryStagingTest, GroupResultsOfAJobInMemoryStayInMemory) {
  const std::unique_ptr<BakeContext> ctx = MemoryJobContext();
  ASSERT_NE(ctx, nullptr);
  const JobPlan& plan = ctx->plan;
  ScratchDir dir;
  const auto store = dir.path() / "held.wbk";
  MemoryStaging memory(2 * RawStagingBytes(plan));  // room for the results
  ASSERT_TRUE(CreateStaging(plan, store).ok());
  for (int t = 0; t < plan.tiles(); ++t)
    ASSERT_TRUE(BakeTile(*ctx, store, t, nullptr, {}, &memory).ok());
  const std::shared_ptr<MemoryStaging::Job> job = memory.Find(store);
  ASSERT_NE(job, nullptr);
  for (int g = 0; g < plan.groups; ++g) {
    GroupStats stats;
    ASSERT_TRUE(TransformColumns(*ctx, store, g, &stats, {}, &memory).ok());
    EXPECT_FALSE(std::filesystem::exists(GroupResultPath(store, g)));
    ASSERT_NE(job->Group(g), nullptr);
    EXPECT_EQ(job->Group(g)->positions.size(), stats.kept);
    EXPECT_EQ(stats.bytes_written, 0u);
  }
  ASSERT_TRUE(Finalize(*ctx, store, {.memory = &memory}).ok());
  EXPECT_EQ(memory.Find(store), nullptr);

  const auto disk = dir.path() / "disk.wbk";
  ASSERT_TRUE(CreateStaging(plan, disk).ok());
  for (int t = 0; t < plan.tiles(); ++t) ASSERT_TRUE(BakeTile(*ctx, disk, t, nullptr).ok());
  ASSERT_TRUE(TransformColumns(*ctx, disk, 0, nullptr, {}, &memory).ok());
  EXPECT_TRUE(std::filesystem::exists(GroupResultPath(disk, 0)));
}

// Group results count against the same budget as the chunks: one that
// would go over is refused (its task writes the file), a group held again
// replaces its own bytes rather than adding to them, and dropping the job
// gives back both.
TEST(MemoryStagingTest, GroupResultsShareTheChunksBudget) {
  const std::unique_ptr<BakeContext> ctx = MemoryJobContext();
  ASSERT_NE(ctx, nullptr);
  const JobPlan& plan = ctx->plan;
  constexpr uint64_t kRoom = 1000;
  MemoryStaging memory(RawStagingBytes(plan) + kRoom);
  ScratchDir dir;
  const auto store = dir.path() / "budget.wbk";
  auto result = [](int g) {
    auto r = std::make_shared<GroupResult>();
    r->group = g;
    return std::shared_ptr<const GroupResult>(r);
  };
  EXPECT_FALSE(memory.HoldGroup(store, 0, result(0), 1));  // not a held job
  ASSERT_NE(memory.Admit(store, plan), nullptr);
  EXPECT_TRUE(memory.HoldGroup(store, 0, result(0), kRoom - 10));
  EXPECT_FALSE(memory.HoldGroup(store, 1, result(1), 11));
  EXPECT_EQ(memory.Find(store)->Group(1), nullptr);
  EXPECT_TRUE(memory.HoldGroup(store, 1, result(1), 10));
  EXPECT_TRUE(memory.HoldGroup(store, 0, result(0), kRoom - 20));  // a retry, smaller
  EXPECT_TRUE(memory.HoldGroup(store, 2, result(2), 10));
  EXPECT_FALSE(memory.HoldGroup(store, 3, result(3), 1));
  EXPECT_EQ(memory.held_bytes(), RawStagingBytes(plan) + kRoom);
  ASSERT_NE(memory.Find(store)->Group(2), nullptr);
  EXPECT_EQ(memory.Find(store)->Group(2)->group, 2);
  memory.Drop(store);
  EXPECT_EQ(memory.held_bytes(), 0u);
}

TEST(MemoryStagingTest, AChunkInNeitherPlaceFailsTheGroupInsteadOfReadingZeros) {
  const std::unique_ptr<BakeContext> ctx = MemoryJobContext();
  ASSERT_NE(ctx, nullptr);
  const JobPlan& plan = ctx->plan;
  ScratchDir dir;
  const auto store = dir.path() / "lost.wbk";
  ASSERT_TRUE(CreateStaging(plan, store).ok());
  {
    // Staged in a memory that is gone (another process's, say).
    MemoryStaging gone(RawStagingBytes(plan));
    for (int t = 0; t < plan.tiles(); ++t)
      ASSERT_TRUE(BakeTile(*ctx, store, t, nullptr, {}, &gone).ok());
  }
  MemoryStaging memory(RawStagingBytes(plan));
  ASSERT_TRUE(BakeTile(*ctx, store, 0, nullptr, {}, &memory).ok());  // a retried tile
  const absl::Status s = TransformColumns(*ctx, store, 0, nullptr, {}, &memory);
  EXPECT_EQ(s.code(), absl::StatusCode::kFailedPrecondition) << s;
  EXPECT_NE(s.message().find("neither in memory nor staged"), std::string::npos) << s;
}

}  // namespace
}  // namespace wavebake
