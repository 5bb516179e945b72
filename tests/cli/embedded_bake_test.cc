// The embedded `wavebake bake` (DESIGN.md §5): a coordinator and workers in
// one process through the cluster's own services. Its store is bit-identical
// to the single-process driver's (worker/local_bake.h) for the same scene and
// parameters (DESIGN.md §1 "Determinism"), whatever the number of workers; a
// failed, refused or interrupted bake leaves nothing at the output.
#include "cli/embedded_bake.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "tests/testing/file_tree.h"
#include "tests/testing/scratch_dir.h"
#include "worker/local_bake.h"

namespace wavebake::cli {
namespace {

using ::testing::HasSubstr;

using test_support::ReadTree;
using test_support::ScratchDir;

std::vector<std::string> Names(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  return names;
}

// 16×16 camera samples in 4 tiles, N = 8: 384 columns in 4 groups.
BakeParams SmallJob() {
  BakeParams p;
  p.light_res = 8;
  p.supersample = 4;
  p.layout = "camera:16x16";
  p.tile_size = 8;
  p.column_group = 100;
  return p;
}

TEST(EmbeddedBakeTest, StoreIsBitIdenticalToTheLocalDriver) {
  ScratchDir dir;
  LocalBakeOptions local;
  local.threads = 2;
  ASSERT_TRUE(
      RunLocalBake("builtin:cylinder-bump", SmallJob(), dir.path() / "local.wbk", local).ok());
  const auto expected = ReadTree(dir.path() / "local.wbk");
  ASSERT_TRUE(expected.contains("transport/indptr/0"));
  for (int workers : {1, 3}) {
    const std::filesystem::path out = dir.path() / ("embedded" + std::to_string(workers) + ".wbk");
    absl::StatusOr<v1::Job> job =
        EmbeddedBake("builtin:cylinder-bump", SmallJob(), out, {.workers = workers, .quiet = true});
    ASSERT_TRUE(job.ok()) << job.status();
    ASSERT_EQ(job->phase(), v1::PHASE_DONE) << job->error();
    EXPECT_EQ(job->tiles(), 4);
    EXPECT_EQ(job->groups(), 4);
    EXPECT_GT(job->rays_traced(), 0);
    EXPECT_TRUE(ReadTree(out) == expected) << workers << " workers";
  }
  // Nothing but the three stores: the coordinator's data dirs are gone.
  EXPECT_THAT(Names(dir.path()),
              ::testing::UnorderedElementsAre("local.wbk", "embedded1.wbk", "embedded3.wbk"));
}

// A scene file is read in place: a JSON scene finds its mesh beside it, and
// the store records the path as given, as the local driver does.
TEST(EmbeddedBakeTest, SceneFilesAreBakedInPlace) {
  ScratchDir dir;
  std::ofstream(dir.path() / "tent.obj")
      << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0.6 0\nf 1 3 2\nf 1 4 3\nf 1 2 5\nf 2 3 5\n";
  std::ofstream(dir.path() / "tent.json") << R"({"meshes": [{"file": "tent.obj"}],
      "camera": {"eye": [0, 2, 3], "target": [0, 0, 0]}})";
  const std::string scene = (dir.path() / "tent.json").string();
  ASSERT_TRUE(RunLocalBake(scene, SmallJob(), dir.path() / "local.wbk", {}).ok());
  absl::StatusOr<v1::Job> job =
      EmbeddedBake(scene, SmallJob(), dir.path() / "embedded.wbk", {.workers = 2, .quiet = true});
  ASSERT_TRUE(job.ok()) << job.status();
  ASSERT_EQ(job->phase(), v1::PHASE_DONE) << job->error();
  EXPECT_TRUE(ReadTree(dir.path() / "embedded.wbk") == ReadTree(dir.path() / "local.wbk"));
}

// The planner cannot see that the camera looks away from everything (it does
// not trace); every worker's BAKE_TILE fails, and the job fails with that
// reason after max_attempts.
TEST(EmbeddedBakeTest, AFailingJobReportsTheWorkersReasonAndLeavesNothing) {
  ScratchDir dir;
  std::ofstream(dir.path() / "tri.obj") << "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 3 2\n";
  std::ofstream(dir.path() / "away.json") << R"({"meshes": [{"file": "tri.obj"}],
      "camera": {"eye": [0, 1, 5], "target": [0, 1, 10]}})";
  absl::StatusOr<v1::Job> job = EmbeddedBake((dir.path() / "away.json").string(), SmallJob(),
                                             dir.path() / "out.wbk", {.workers = 2, .quiet = true});
  ASSERT_TRUE(job.ok()) << job.status();
  EXPECT_EQ(job->phase(), v1::PHASE_FAILED);
  EXPECT_THAT(job->error(), HasSubstr("no sample hits the scene"));
  EXPECT_THAT(Names(dir.path()), ::testing::UnorderedElementsAre("tri.obj", "away.json"));
}

TEST(EmbeddedBakeTest, RefusedInputLeavesNothing) {
  ScratchDir dir;
  absl::StatusOr<v1::Job> job = EmbeddedBake("builtin:no-such-scene", SmallJob(),
                                             dir.path() / "out.wbk", {.workers = 1, .quiet = true});
  EXPECT_EQ(job.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(job.status().message()), ::testing::StartsWith("scene.builtin: "));
  job = EmbeddedBake((dir.path() / "missing.obj").string(), SmallJob(), dir.path() / "out.wbk",
                     {.workers = 1, .quiet = true});
  EXPECT_EQ(job.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(EmbeddedBakeTest, AnInterruptedBakeIsCancelledAndLeavesNothing) {
  ScratchDir dir;
  const std::atomic<bool> interrupted{true};
  absl::StatusOr<v1::Job> job =
      EmbeddedBake("builtin:sphere-plane", SmallJob(), dir.path() / "out.wbk",
                   {.workers = 1, .quiet = true, .interrupted = &interrupted});
  ASSERT_TRUE(job.ok()) << job.status();
  EXPECT_EQ(job->phase(), v1::PHASE_CANCELLED);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace wavebake::cli
