// The embedded `wavebake bake` (DESIGN.md §5): a coordinator and workers in
// one process through the cluster's own services. Its store is bit-identical
// whatever the number of workers and to the three tasks driven by hand in a
// shuffled order with retries (DESIGN.md §1 "Determinism"); it passes the
// white furnace through the whole pipeline; its events add up; and a failed,
// refused or interrupted bake leaves nothing at the output.
#include "driver/bake/embedded_bake.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <random>
#include <set>

#include "core/bake/bake_params_io.h"
#include "core/wavelets/wavelet2d.h"
#include "storage/store/store_reader.h"
#include "tests/testing/file_tree.h"
#include "tests/testing/scratch_dir.h"
#include "worker/columns/finalize.h"
#include "worker/columns/publish_store.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/staging.h"

namespace wavebake::driver {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

using test_support::ReadTree;
using test_support::ScratchDir;

std::vector<std::string> Names(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  return names;
}

constexpr char kScene[] = "builtin:cylinder-bump";

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

absl::StatusOr<v1::Job> Bake(const std::filesystem::path& out, int workers,
                             const BakeParams& p = SmallJob(), const std::string& scene = kScene,
                             std::function<void(const v1::JobEvent&)> on_event = {}) {
  absl::StatusOr<v1::Job> job =
      EmbeddedBake(scene, p, out, {.workers = workers, .on_event = std::move(on_event)});
  if (job.ok() && job->phase() != v1::PHASE_DONE)
    return absl::InternalError(absl::StrCat("job ended ", job->phase(), ": ", job->error()));
  return job;
}

TEST(EmbeddedBakeTest, BitIdenticalAcrossWorkersAndToShuffledRetriedTasks) {
  ASSERT_TRUE(SmallJob().refine);  // the default: rows traced by visibility refinement
  ScratchDir dir;
  const auto one = dir.path() / "one.wbk";
  absl::StatusOr<v1::Job> job = Bake(one, 1);
  ASSERT_TRUE(job.ok()) << job.status();
  EXPECT_EQ(job->tiles(), 4);
  EXPECT_EQ(job->groups(), 4);
  const auto expected = ReadTree(one);
  ASSERT_TRUE(expected.contains("transport/indptr/0"));
  ASSERT_TRUE(Bake(dir.path() / "three.wbk", 3).ok());
  EXPECT_TRUE(ReadTree(dir.path() / "three.wbk") == expected);

  // The tasks driven by hand in a shuffled order, with a retried tile and group.
  const auto manual = dir.path() / "manual.wbk";
  auto ctx = MakeBakeContext(kScene, SmallJob());
  ASSERT_TRUE(ctx.ok()) << ctx.status();
  const JobPlan& plan = (*ctx)->plan;
  std::mt19937 rng(7);
  std::vector<int> tiles(plan.tiles()), groups(plan.groups);
  std::iota(tiles.begin(), tiles.end(), 0);
  std::iota(groups.begin(), groups.end(), 0);
  std::shuffle(tiles.begin(), tiles.end(), rng);
  std::shuffle(groups.begin(), groups.end(), rng);
  tiles.push_back(tiles.front());
  groups.push_back(groups.front());
  ASSERT_TRUE(CreateStaging(plan, manual).ok());
  for (int t : tiles) ASSERT_TRUE(BakeTile(**ctx, manual, t, nullptr).ok());
  for (int g : groups) ASSERT_TRUE(TransformColumns(**ctx, manual, g, nullptr).ok());
  ASSERT_TRUE(Finalize(**ctx, manual, {}).ok());
  EXPECT_TRUE(ReadTree(manual) == expected);
  // Nothing but the stores: the coordinators' data dirs are gone.
  EXPECT_THAT(Names(dir.path()),
              ::testing::UnorderedElementsAre("one.wbk", "three.wbk", "manual.wbk"));
}

// FINALIZE runs as tasks (core/bake/finalize_shards.h): 4 groups make 4 shards
// and a last task, each done once, the last after every shard; with 2
// workers the store is the 1-worker store byte for byte.
TEST(EmbeddedBakeTest, FinalizeRunsAsShardTasksAndTheStoreIsTheOneWorkerStore) {
  ScratchDir dir;
  ASSERT_TRUE(Bake(dir.path() / "one.wbk", 1).ok());
  std::vector<int> finalize_done;  // task indices, in the order they were done
  std::set<std::string> finalize_workers;
  absl::StatusOr<v1::Job> job =
      Bake(dir.path() / "two.wbk", 2, SmallJob(), kScene, [&](const v1::JobEvent& e) {
        if (e.kind() == v1::EVENT_TASK_DONE && e.task_kind() == v1::FINALIZE) {
          finalize_done.push_back(e.task_index());
          finalize_workers.insert(e.worker_id());
        }
      });
  ASSERT_TRUE(job.ok()) << job.status();
  ASSERT_EQ(job->groups(), 4);
  EXPECT_EQ(job->tasks_total(), job->tiles() + 4 + 4 + 1);
  ASSERT_EQ(finalize_done.size(), 5u);
  EXPECT_EQ(finalize_done.back(), 4);  // the last task, after the shards
  EXPECT_THAT(std::vector<int>(finalize_done.begin(), finalize_done.end() - 1),
              ::testing::UnorderedElementsAre(0, 1, 2, 3));
  std::cout << "FINALIZE tasks done by " << finalize_workers.size() << " worker(s)\n";
  EXPECT_TRUE(ReadTree(dir.path() / "two.wbk") == ReadTree(dir.path() / "one.wbk"));
}

// .zattrs records refinement (params.refine and the options), and a
// brute-force store carries neither key: its bytes are those of every store
// baked before refinement existed. Brute force traces many more rays.
TEST(EmbeddedBakeTest, StoreRecordsTheVisibilityMethod) {
  ScratchDir dir;
  BakeParams p = SmallJob();
  p.light_res = 16;
  absl::StatusOr<v1::Job> refined = Bake(dir.path() / "refined.wbk", 2, p);
  ASSERT_TRUE(refined.ok()) << refined.status();
  p.refine = false;
  absl::StatusOr<v1::Job> brute = Bake(dir.path() / "brute.wbk", 2, p);
  ASSERT_TRUE(brute.ok()) << brute.status();
  absl::StatusOr<StoreInfo> on = ReadStoreInfo(dir.path() / "refined.wbk");
  absl::StatusOr<StoreInfo> off = ReadStoreInfo(dir.path() / "brute.wbk");
  ASSERT_TRUE(on.ok() && off.ok());
  EXPECT_TRUE(on->params.refine);
  EXPECT_EQ(on->attrs["params"]["refine"], "on");
  EXPECT_EQ(on->attrs["refinement"]["start_spacing"], 2);  // N/8
  EXPECT_EQ(on->attrs["refinement"]["stagger"], true);
  EXPECT_EQ(on->attrs["refinement"]["follow"], true);
  EXPECT_FALSE(off->params.refine);
  EXPECT_FALSE(off->attrs["params"].contains("refine"));
  EXPECT_FALSE(off->attrs.contains("refinement"));
  EXPECT_LT(refined->rays_traced(), brute->rays_traced() / 2);
}

// L ≡ 1 on builtin:furnace: B = Σ_m T[s,m] = 1 for every sample. With the
// Haar row transform the pixel sum of a face is N × its scaling coefficient
// (column face·N²), so B is six decoded, inverse-column-transformed columns.
TEST(EmbeddedBakeTest, WhiteFurnaceSurvivesTheWholePipeline) {
  ScratchDir dir;
  const auto out = dir.path() / "furnace.wbk";
  BakeParams p = SmallJob();
  p.layout = "camera:32x32";
  p.tile_size = 16;
  ASSERT_TRUE(Bake(out, 2, p, "builtin:furnace").ok());
  absl::StatusOr<SampleSet> samples = ReadSamples(out);
  ASSERT_TRUE(samples.ok()) << samples.status();
  std::vector<double> b(32 * 32, 0.0);
  for (int face = 0; face < 6; ++face) {
    absl::StatusOr<DecodedColumn> c = ReadColumn(out, face * 64);
    ASSERT_TRUE(c.ok()) << c.status();
    std::vector<float> img(32 * 32, 0.0f);
    for (size_t k = 0; k < c->positions.size(); ++k) img[c->positions[k]] = c->values[k];
    Inverse2d(WaveletFilter::kHaar, img, 32, 32, c->depth);
    for (int i = 0; i < 32 * 32; ++i) b[i] += 8.0 * img[i];
  }
  double sum2 = 0;
  int n = 0;
  for (int i = 0; i < 32 * 32; ++i) {
    if (samples->grid[i] < 0) continue;
    sum2 += (b[i] - 1) * (b[i] - 1);
    ++n;
  }
  ASSERT_GT(n, 512);
  EXPECT_LT(std::sqrt(sum2 / n), 0.01) << "rms |B − 1| over " << n << " samples";
}

// The events a watcher sees run through the three phases in order, each
// phase's task count within its total, rays never decreasing, and end at the
// job's own totals; the stats agree with the store.
TEST(EmbeddedBakeTest, EventsAndStatsAddUp) {
  ScratchDir dir;
  const auto out = dir.path() / "out.wbk";
  std::vector<v1::JobEvent> seen;
  absl::StatusOr<v1::Job> job =
      Bake(out, 2, SmallJob(), kScene, [&](const v1::JobEvent& e) { seen.push_back(e); });
  ASSERT_TRUE(job.ok()) << job.status();
  ASSERT_FALSE(seen.empty());
  std::vector<v1::Phase> order;
  int64_t rays = 0;
  for (const v1::JobEvent& e : seen) {
    if (order.empty() || order.back() != e.phase()) order.push_back(e.phase());
    EXPECT_LE(e.phase_tasks_done(), e.phase_tasks_total());
    EXPECT_GE(e.rays_traced(), rays);
    rays = e.rays_traced();
  }
  EXPECT_THAT(order,
              ::testing::ElementsAre(v1::PHASE_QUEUED, v1::PHASE_BAKING, v1::PHASE_TRANSFORMING,
                                     v1::PHASE_FINALIZING, v1::PHASE_DONE));
  EXPECT_EQ(seen.back().tasks_done(), job->tasks_total());
  EXPECT_EQ(seen.back().rays_traced(), job->rays_traced());
  // At most K = 4 rays per (sample, texel); horizon culling skips some.
  EXPECT_GT(job->rays_traced(), 0);
  EXPECT_LE(job->rays_traced(), 16 * 16 * 384 * 4);
  const nlohmann::json stats = nlohmann::json::parse(job->stats_json());
  absl::StatusOr<CompressedColumns> t = ReadTransport(out);
  ASSERT_TRUE(t.ok()) << t.status();
  EXPECT_EQ(stats.at("nnz").get<int64_t>(), t->indptr.back());
  // Matrix scope: the mean column error ≤ their RMS = the matrix error ≤
  // t·sqrt(1 + 3/4) (dropped ≤ t², dither ≤ 3× its expected (t/2)² budget).
  EXPECT_LE(stats.at("column_error").at("mean").get<double>(), 0.01 * std::sqrt(1.75) * 1.000001);
}

TEST(EmbeddedBakeTest, InvalidParametersNameTheFieldAndLeaveNothing) {
  ScratchDir dir;
  struct Case {
    const char* field;
    std::function<void(BakeParams&)> spoil;
  };
  const Case cases[] = {
      {"bits", [](BakeParams& p) { p.bits = 1; }},
      {"bits", [](BakeParams& p) { p.bits = 17; }},
      {"target_error", [](BakeParams& p) { p.target_error = -0.01; }},
      {"column_filter", [](BakeParams& p) { p.column_filter = WaveletFilter::kDaub4; }},
      {"light_res", [](BakeParams& p) { p.light_res = 12; }},
      {"layout", [](BakeParams& p) { p.layout = "spiral"; }},
  };
  for (const Case& c : cases) {
    BakeParams p = SmallJob();
    c.spoil(p);
    absl::StatusOr<v1::Job> job = EmbeddedBake(kScene, p, dir.path() / "bad.wbk", {.workers = 1});
    EXPECT_EQ(job.status().code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_THAT(job.status().message(), HasSubstr(c.field));
    EXPECT_THAT(Names(dir.path()), IsEmpty()) << c.field;
  }
  // Unknown names are refused where strings become params (CLI, RPC, store).
  EXPECT_THAT(ParseWaveletFilter("db8").status().message(), HasSubstr("filter"));
  EXPECT_THAT(ParseColumnMode("fast").status().message(), HasSubstr("column_mode"));
  absl::StatusOr<v1::Job> job =
      EmbeddedBake("builtin:no-such-scene", SmallJob(), dir.path() / "out.wbk", {.workers = 1});
  EXPECT_EQ(job.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(job.status().message()), ::testing::StartsWith("scene.builtin: "));
  job = EmbeddedBake((dir.path() / "missing.obj").string(), SmallJob(), dir.path() / "out.wbk",
                     {.workers = 1});
  EXPECT_EQ(job.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(Names(dir.path()), IsEmpty());
}

TEST(EmbeddedBakeTest, RefusesToOverwriteWhatIsNotAStore) {
  ScratchDir dir;
  const auto out = dir.path() / "precious.txt";
  { std::ofstream(out) << "keep me"; }
  absl::StatusOr<v1::Job> job = Bake(out, 1);
  EXPECT_EQ(job.status().code(), absl::StatusCode::kAlreadyExists) << job.status();
  EXPECT_THAT(job.status().message(), HasSubstr("out"));
  EXPECT_EQ(ReadTree(dir.path()).at("precious.txt"), "keep me");
  EXPECT_THAT(Names(dir.path()), ::testing::ElementsAre("precious.txt"));
  job = Bake(dir.path() / "no_dir" / "x.wbk", 1);
  EXPECT_EQ(job.status().code(), absl::StatusCode::kInvalidArgument) << job.status();
}

TEST(EmbeddedBakeTest, ReplacesAnExistingStoreWhole) {
  ScratchDir dir;
  const auto out = dir.path() / "out.wbk";
  ASSERT_TRUE(Bake(out, 2).ok());
  BakeParams p = SmallJob();
  p.column_mode = ColumnMode::k2d;
  p.bits = 9;
  ASSERT_TRUE(Bake(out, 2, p).ok());
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(out);
  ASSERT_TRUE(info.ok()) << info.status();
  EXPECT_EQ(info->params.column_mode, ColumnMode::k2d);
  EXPECT_EQ(info->bits, 9);
  // Same bytes as a fresh bake of the new params: nothing of the old store remains.
  ASSERT_TRUE(Bake(dir.path() / "fresh.wbk", 1, p).ok());
  EXPECT_TRUE(ReadTree(out) == ReadTree(dir.path() / "fresh.wbk"));
  EXPECT_THAT(Names(dir.path()), ::testing::UnorderedElementsAre("out.wbk", "fresh.wbk"));
}

// Replacing a store deletes it: a file of the user's inside used to go with
// it without a word. Now the replacement is refused naming the file, which
// stays; a store with its kept staging (--keep-staging) is still replaced.
TEST(EmbeddedBakeTest, RefusesToReplaceAStoreHoldingAUsersFile) {
  ScratchDir dir;
  const auto out = dir.path() / "out.wbk";
  BakeParams keep = SmallJob();
  keep.keep_staging = true;
  ASSERT_TRUE(Bake(out, 2, keep).ok());
  ASSERT_TRUE(std::filesystem::exists(out / "staging" / "groups"));
  ASSERT_TRUE(std::filesystem::exists(out / "staging" / "finalize" / "plan.wbp"));
  ASSERT_TRUE(Bake(out, 2).ok()) << "kept staging is the bake's own";
  for (const std::filesystem::path& foreign :
       {out / "notes.txt", out / "transport" / "data" / "notes.txt", out / "mine" / "x.bin"}) {
    std::filesystem::create_directories(foreign.parent_path());
    { std::ofstream(foreign) << "keep me"; }
    absl::StatusOr<v1::Job> job = Bake(out, 2);
    EXPECT_EQ(job.status().code(), absl::StatusCode::kAlreadyExists) << job.status();
    const bool in_own_dir = foreign.parent_path().filename() == "mine";  // not a Zarr node
    EXPECT_THAT(job.status().message(),
                HasSubstr((in_own_dir ? foreign.parent_path() : foreign).string() + ","));
    EXPECT_EQ(ReadTree(dir.path()).at(std::filesystem::relative(foreign, dir.path()).string()),
              "keep me");
    EXPECT_THAT(Names(dir.path()), ::testing::ElementsAre("out.wbk"));
    std::filesystem::remove_all(in_own_dir ? foreign.parent_path() : foreign);
  }
}

// --out through a symbolic link: the store goes to the link's target (it used
// to fail with "INTERNAL: rename … Not a directory"); a link given to the
// bake itself is refused clearly.
TEST(EmbeddedBakeTest, ASymlinkedOutputIsResolvedToItsTarget) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.path() / "disk");
  const auto link = dir.path() / "out.wbk";
  std::filesystem::create_symlink("disk/real.wbk", link);  // dangling: nothing baked yet
  absl::StatusOr<std::filesystem::path> resolved = ResolveOutputPath(link);
  ASSERT_TRUE(resolved.ok()) << resolved.status();
  EXPECT_EQ(*resolved, dir.path() / "disk/real.wbk");
  ASSERT_TRUE(Bake(*resolved, 2).ok());
  ASSERT_TRUE(ReadStoreInfo(link).ok()) << "readable through the link";
  ASSERT_TRUE(Bake(*ResolveOutputPath(link), 2).ok()) << "replaced through the link";
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_THAT(Names(dir.path() / "disk"), ::testing::ElementsAre("real.wbk"));

  const absl::StatusOr<v1::Job> refused = Bake(link, 1);
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(refused.status().message(), HasSubstr("symbolic link"));
  std::filesystem::create_symlink("loop", dir.path() / "loop");
  EXPECT_THAT(ResolveOutputPath(dir.path() / "loop").status().message(),
              HasSubstr("too many levels"));
}

// A failure midway (here: FINALIZE's shards cannot write their plan and
// outcomes) fails the job, removes the coordinator's data dir with the
// partial store and leaves an existing store untouched.
TEST(EmbeddedBakeTest, FailureMidwayLeavesNothingBehind) {
  ScratchDir dir;
  const auto out = dir.path() / "out.wbk";
  ASSERT_TRUE(Bake(out, 1).ok());
  const auto before = ReadTree(out);
  bool sabotaged = false;
  auto sabotage = [&](const v1::JobEvent& e) {
    if (e.phase() != v1::PHASE_BAKING || sabotaged) return;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
      const auto staging = entry.path() / "store" / ".bake.wbk.partial" / "staging";
      if (std::filesystem::is_directory(staging)) {
        std::filesystem::remove_all(staging / "finalize");
        std::ofstream(staging / "finalize") << "not a directory";
        sabotaged = true;
      }
    }
  };
  absl::StatusOr<v1::Job> job =
      EmbeddedBake(kScene, SmallJob(), out, {.workers = 2, .on_event = sabotage});
  EXPECT_TRUE(sabotaged);
  ASSERT_TRUE(job.ok()) << job.status();
  EXPECT_EQ(job->phase(), v1::PHASE_FAILED);
  EXPECT_TRUE(ReadTree(out) == before);
  EXPECT_THAT(Names(dir.path()), ::testing::ElementsAre("out.wbk"));
}

// A scene file is read in place: a JSON scene finds its mesh beside it.
TEST(EmbeddedBakeTest, SceneFilesAreBakedInPlace) {
  ScratchDir dir;
  std::ofstream(dir.path() / "tent.obj")
      << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0.6 0\nf 1 3 2\nf 1 4 3\nf 1 2 5\nf 2 3 5\n";
  std::ofstream(dir.path() / "tent.json") << R"({"meshes": [{"file": "tent.obj"}],
      "camera": {"eye": [0, 2, 3], "target": [0, 0, 0]}})";
  const std::string scene = (dir.path() / "tent.json").string();
  ASSERT_TRUE(Bake(dir.path() / "a.wbk", 2, SmallJob(), scene).ok());
  absl::StatusOr<SampleSet> samples = ReadSamples(dir.path() / "a.wbk");
  ASSERT_TRUE(samples.ok()) << samples.status();
  ASSERT_GT(samples->size(), 0);
  for (int s = 0; s < samples->size(); ++s) {  // every sample on the tent
    EXPECT_GE(samples->position[s].y, -1e-4f);
    EXPECT_LE(samples->position[s].y, 0.6f + 1e-4f);
  }
}

// The planner cannot see that the camera looks away from everything (it does
// not trace); every worker's BAKE_TILE fails, and the job fails with that
// reason.
TEST(EmbeddedBakeTest, AFailingJobReportsTheWorkersReasonAndLeavesNothing) {
  ScratchDir dir;
  std::ofstream(dir.path() / "tri.obj") << "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 3 2\n";
  std::ofstream(dir.path() / "away.json") << R"({"meshes": [{"file": "tri.obj"}],
      "camera": {"eye": [0, 1, 5], "target": [0, 1, 10]}})";
  absl::StatusOr<v1::Job> job = EmbeddedBake((dir.path() / "away.json").string(), SmallJob(),
                                             dir.path() / "out.wbk", {.workers = 2});
  ASSERT_TRUE(job.ok()) << job.status();
  EXPECT_EQ(job->phase(), v1::PHASE_FAILED);
  EXPECT_THAT(job->error(), HasSubstr("no sample hits the scene"));
  EXPECT_THAT(Names(dir.path()), ::testing::UnorderedElementsAre("tri.obj", "away.json"));
}

TEST(EmbeddedBakeTest, AnInterruptedBakeIsCancelledAndLeavesNothing) {
  ScratchDir dir;
  const std::atomic<bool> interrupted{true};
  absl::StatusOr<v1::Job> job =
      EmbeddedBake("builtin:sphere-plane", SmallJob(), dir.path() / "out.wbk",
                   {.workers = 1, .interrupted = &interrupted});
  ASSERT_TRUE(job.ok()) << job.status();
  EXPECT_EQ(job->phase(), v1::PHASE_CANCELLED);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace wavebake::driver
