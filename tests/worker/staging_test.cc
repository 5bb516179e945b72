#include "worker/tiles/staging.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <thread>
#include <vector>

#include "core/bake/job_plan.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"
#include "tests/worker/staging_testing.h"

namespace wavebake {
namespace {

using staging_testing::ScratchDir;

JobPlan Plan(int light_res, int width, int height, int tile_size, int column_group) {
  BakeParams p;
  p.light_res = light_res;
  p.tile_size = tile_size;
  p.column_group = column_group;
  return MakeJobPlan(p, width, height);
}

// The shapes of storage/store/store_layout.h, spelled out from N, W, H and the task
// sizes: [6N², W·H] chunked [group, tile edge²], and one energy per tile.
TEST(StagingTest, CreatesBothArraysWithTheDocumentedLayout) {
  ScratchDir dir;
  const std::filesystem::path store = dir.path() / "out.wbk";
  ASSERT_TRUE(CreateStaging(Plan(8, 32, 16, 8, 100), store).ok());
  EXPECT_TRUE(std::filesystem::exists(store / ".zgroup"));
  EXPECT_TRUE(std::filesystem::exists(store / "staging" / ".zgroup"));

  absl::StatusOr<ZarrArray> transport = ZarrArray::Open(store / "staging" / "transport");
  ASSERT_TRUE(transport.ok()) << transport.status();
  EXPECT_EQ(transport->spec().shape, (std::vector<int64_t>{6 * 8 * 8, 32 * 16}));
  EXPECT_EQ(transport->spec().chunks, (std::vector<int64_t>{100, 8 * 8}));
  EXPECT_EQ(transport->spec().dtype, DType::kFloat32);
  EXPECT_EQ(transport->spec().fill_value, 0);
  EXPECT_EQ(transport->chunk_grid(), (std::vector<int64_t>{4, 8}));  // 384 = 3·100 + 84

  absl::StatusOr<ZarrArray> energy = ZarrArray::Open(store / "staging" / "tile_energy");
  ASSERT_TRUE(energy.ok()) << energy.status();
  EXPECT_EQ(energy->spec().shape, (std::vector<int64_t>{8}));
  EXPECT_EQ(energy->spec().chunks, (std::vector<int64_t>{1}));
  EXPECT_EQ(energy->spec().dtype, DType::kFloat32);
}

// Every worker calls it before its first tile: a second call (also
// concurrent ones) must keep the arrays and the chunks already written.
TEST(StagingTest, IsIdempotentAndKeepsChunks) {
  ScratchDir dir;
  const std::filesystem::path store = dir.path() / "out.wbk";
  const JobPlan plan = Plan(8, 16, 16, 8, 256);
  ASSERT_TRUE(CreateStaging(plan, store).ok());
  absl::StatusOr<ZarrArray> energy = ZarrArray::Open(store::Path(store, store::kStagingTileEnergy));
  ASSERT_TRUE(energy.ok());
  const int64_t index[] = {2};
  const float value[] = {42.5f};
  ASSERT_TRUE(energy->WriteChunk<float>(index, value).ok());

  std::vector<std::thread> workers;
  std::vector<absl::Status> results(4);
  for (int i = 0; i < 4; ++i) {
    workers.emplace_back([&, i] { results[i] = CreateStaging(plan, store); });
  }
  for (std::thread& t : workers) t.join();
  for (const absl::Status& s : results) EXPECT_TRUE(s.ok()) << s;

  absl::StatusOr<std::vector<float>> kept = energy->ReadChunk<float>(index);
  ASSERT_TRUE(kept.ok());
  EXPECT_EQ((*kept)[0], 42.5f);
}

TEST(StagingTest, AnotherPlanIsAlreadyExists) {
  ScratchDir dir;
  const std::filesystem::path store = dir.path() / "out.wbk";
  ASSERT_TRUE(CreateStaging(Plan(8, 16, 16, 8, 256), store).ok());
  const absl::Status s = CreateStaging(Plan(8, 16, 16, 8, 128), store);
  EXPECT_TRUE(absl::IsAlreadyExists(s)) << s;
  EXPECT_NE(s.message().find("transport"), std::string::npos) << s;
}

}  // namespace
}  // namespace wavebake
