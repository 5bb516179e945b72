// The real planner (DESIGN.md §2, §4): tasks from the layout's grid without
// tracing, scenes from built-ins or uploads, bad scenes named by their field,
// the partial store reserved once, and cleanup of ended jobs.
#include "coordinator/service/job_planner.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "absl/strings/str_cat.h"
#include "coordinator/state/scene_store.h"
#include "proto/bake_request.h"
#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

class JobPlannerTest : public ::testing::Test {
 protected:
  PlannerOptions Options() {
    return {.data_dir = dir_.path(), .store_root = dir_.path() / "store", .local_scenes = {}};
  }

  // A request as Submit hands it to the planner: normalized, output named.
  static v1::BakeRequest Request(v1::BakeRequest r, const std::string& output = "job.wbk") {
    EXPECT_TRUE(NormalizeBakeRequest(r).ok());
    r.set_output_name(output);
    return r;
  }

  // Puts bytes where UploadScene would and returns the request's SceneRef.
  v1::BakeRequest Uploaded(const std::string& bytes, const std::string& file_name) {
    const std::string sha = Sha256Hex(bytes);
    const std::filesystem::path blob = SceneStore::BlobPath(dir_.path(), sha);
    std::filesystem::create_directories(blob.parent_path());
    std::ofstream(blob, std::ios::binary) << bytes;
    v1::BakeRequest r;
    r.mutable_scene()->mutable_uploaded()->set_sha256(sha);
    r.mutable_scene()->mutable_uploaded()->set_file_name(file_name);
    return r;
  }

  testing::TempDir dir_;
};

// camera:32x32 in tiles of 16 is 2×2 tiles; N = 8 gives M = 384 columns, in
// groups of 100 that is 4 groups (the last one short). Rays: every cell, K =
// 4 directions per texel, half of the texels above the horizon.
TEST_F(JobPlannerTest, CutsTheLayoutGridIntoTilesAndGroups) {
  v1::BakeRequest r = testing::BuiltinRequest("builtin:sphere-plane");
  r.set_light_res(8);
  r.set_layout("camera:32x32");
  r.set_tile_size(16);
  r.set_column_group(100);
  absl::StatusOr<PlannedJob> plan = MakeJobPlanner(Options())(Request(r));
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->tiles, 4);
  EXPECT_EQ(plan->groups, 4);
  EXPECT_EQ(plan->total_rays_estimate, int64_t{32} * 32 * 384 * 4 / 2);
  EXPECT_TRUE(plan->store_path.empty());  // the request's output_name
}

// The grid layout takes its size from the built-ins' 64×64 ground mesh.
TEST_F(JobPlannerTest, GridLayoutTakesTheMeshGrid) {
  v1::BakeRequest r = testing::BuiltinRequest("builtin:disk-over-plane");
  r.set_layout("grid");
  r.set_light_res(8);
  absl::StatusOr<PlannedJob> plan = MakeJobPlanner(Options())(Request(r));
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->tiles, (64 / 32) * (64 / 32));
  EXPECT_EQ(plan->groups, 1);  // the plan's group size: all 384 columns of 64² cells at once
}

TEST_F(JobPlannerTest, SupersamplingIsRoundedUpToASquare) {
  EXPECT_EQ(EstimateRays(4, 6 * 8 * 8, 4), 4 * 384 * 4 / 2);
  EXPECT_EQ(EstimateRays(4, 6 * 8 * 8, 5), 4 * 384 * 9 / 2);
  EXPECT_EQ(EstimateRays(4, 6 * 8 * 8, 1), 4 * 384 / 2);
}

TEST_F(JobPlannerTest, PlansAnUploadedMeshByItsFileName) {
  std::ifstream in(std::filesystem::path(WB_SHARED_DATA) / "models" / "bunny.obj");
  const std::string bunny((std::istreambuf_iterator<char>(in)), {});
  ASSERT_FALSE(bunny.empty());
  v1::BakeRequest r = Uploaded(bunny, "bunny.obj");
  r.set_layout("hilbert:64x64");  // 2503 vertices fit in 4096 cells
  r.set_light_res(8);
  absl::StatusOr<PlannedJob> plan = MakeJobPlanner(Options())(Request(r));
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->tiles, 4);
  // Only the vertices trace (the bunny file says 2503 of them).
  EXPECT_EQ(plan->total_rays_estimate, int64_t{2503} * 384 * 4 / 2);
}

TEST_F(JobPlannerTest, BadScenesAreInvalidArgumentNamingTheField) {
  const PlanFn plan = MakeJobPlanner(Options());
  absl::StatusOr<PlannedJob> unknown =
      plan(Request(testing::BuiltinRequest("builtin:no-such-scene"), "a.wbk"));
  EXPECT_EQ(unknown.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(unknown.status().message()), StartsWith("scene.builtin: "));

  // A vertex that is not a number (DESIGN.md §4's "NaN vertices").
  absl::StatusOr<PlannedJob> nan =
      plan(Request(Uploaded("v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", "nan.obj"), "b.wbk"));
  EXPECT_EQ(nan.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(nan.status().message()),
              StartsWith("scene.uploaded: scene file 'nan.obj' (sha256 "));
  EXPECT_THAT(std::string(nan.status().message()), HasSubstr("not finite"));

  absl::StatusOr<PlannedJob> empty = plan(Request(Uploaded("# nothing\n", "empty.obj"), "c.wbk"));
  EXPECT_EQ(empty.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(empty.status().message()), StartsWith("scene.uploaded: "));

  // A mesh file has no regular grid for the grid layout.
  v1::BakeRequest grid = Uploaded("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "tri.obj");
  grid.set_layout("grid");
  absl::StatusOr<PlannedJob> no_grid = plan(Request(grid, "d.wbk"));
  EXPECT_EQ(no_grid.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(no_grid.status().message()), StartsWith("layout: "));

  // Layouts that do not fit the scene are refused here, before any task
  // runs (they used to fail only inside BAKE_TILE): camera needs a camera, a
  // hilbert grid a cell per vertex.
  v1::BakeRequest no_camera = Uploaded("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "tri.obj");
  no_camera.set_layout("camera:16x16");
  absl::StatusOr<PlannedJob> camera = plan(Request(no_camera, "e.wbk"));
  EXPECT_EQ(camera.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(camera.status().message()), StartsWith("layout: camera:16x16 needs"));
  v1::BakeRequest small = Uploaded("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "tri.obj");
  small.set_layout("hilbert:1x2");
  absl::StatusOr<PlannedJob> hilbert = plan(Request(small, "f.wbk"));
  EXPECT_EQ(hilbert.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(hilbert.status().message()),
              StartsWith("layout: hilbert:1x2: scene 'tri' has 3 vertices, more than the 2 cells"));
  small.set_layout("hilbert:2x2");
  EXPECT_TRUE(plan(Request(small, "g.wbk")).ok());

  // Nothing was reserved for the refused jobs.
  for (const char* name : {"a.wbk", "b.wbk", "c.wbk", "d.wbk", "e.wbk", "f.wbk"})
    EXPECT_FALSE(std::filesystem::exists(Options().store_root / PartialStorePath(name))) << name;
}

// A JSON scene names its meshes relative to itself: planned from the upload
// alone its mesh is missing, planned in place (the embedded bake) it loads.
TEST_F(JobPlannerTest, LocalScenesArePlannedInPlace) {
  const std::filesystem::path scene_dir = dir_.path() / "scene";
  std::filesystem::create_directories(scene_dir);
  std::ofstream(scene_dir / "tri.obj") << "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 3 2\n";
  const std::string json = R"({"meshes": [{"file": "tri.obj"}]})";
  std::ofstream(scene_dir / "scene.json") << json;
  v1::BakeRequest r = Uploaded(json, "scene.json");
  r.set_layout("hilbert:4x4");
  r.set_light_res(8);

  absl::StatusOr<PlannedJob> remote = MakeJobPlanner(Options())(Request(r, "remote.wbk"));
  EXPECT_EQ(remote.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(remote.status().message()), HasSubstr("tri.obj"));

  PlannerOptions local = Options();
  local.local_scenes[r.scene().uploaded().sha256()] = (scene_dir / "scene.json").string();
  absl::StatusOr<PlannedJob> plan = MakeJobPlanner(local)(Request(r, "local.wbk"));
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->tiles, 1);
}

// An uploaded JSON scene reaches no file of the coordinator's disk: a mesh
// named by an absolute path, or by ".." out of the upload, is refused naming
// the field (it used to bake, and its vertices could then be fetched), and
// the message carries no path of the server.
TEST_F(JobPlannerTest, UploadedJsonScenesReadNoServerFile) {
  const std::filesystem::path server_mesh = dir_.path() / "server.obj";
  std::ofstream(server_mesh) << "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 3 2\n";
  int n = 0;
  for (const std::string& reference :
       {server_mesh.string(), std::string("../../server.obj"), std::string("/etc/passwd")}) {
    v1::BakeRequest r = Uploaded(R"({"meshes": [{"file": ")" + reference + R"("}]})", "evil.json");
    r.set_layout("hilbert:4x4");
    r.set_light_res(8);
    absl::StatusOr<PlannedJob> plan =
        MakeJobPlanner(Options())(Request(r, absl::StrCat("evil", n++, ".wbk")));
    ASSERT_FALSE(plan.ok()) << reference;
    EXPECT_EQ(plan.status().code(), absl::StatusCode::kInvalidArgument);
    const std::string message(plan.status().message());
    EXPECT_THAT(message, StartsWith("scene.uploaded: scene file 'evil.json' (sha256 ")) << message;
    EXPECT_THAT(message, HasSubstr("meshes[0].file")) << message;
    const std::string data_dir = dir_.path().string();
    EXPECT_EQ(message.find(data_dir, message.find(reference) + reference.size()), std::string::npos)
        << "names a server path beyond the reference itself: " << message;
  }
}

TEST_F(JobPlannerTest, ReservesThePartialStoreOnceAndCleanupRemovesIt) {
  const PlanFn plan = MakeJobPlanner(Options());
  const v1::BakeRequest r = Request(testing::BuiltinRequest(), "same.wbk");
  ASSERT_TRUE(plan(r).ok());
  const std::filesystem::path partial = Options().store_root / PartialStorePath("same.wbk");
  EXPECT_TRUE(std::filesystem::exists(partial / kPartialMarker));
  absl::StatusOr<PlannedJob> again = plan(r);
  EXPECT_EQ(again.status().code(), absl::StatusCode::kAlreadyExists);
  EXPECT_THAT(std::string(again.status().message()), StartsWith("output_name: "));

  // A FINALIZE that published before the job was cancelled leaves a store too.
  std::filesystem::create_directories(Options().store_root / "same.wbk" / "transport");
  JobRecord job;
  job.id = 7;
  job.store_path = "same.wbk";
  MakeJobCleanup(Options().store_root)(job);
  EXPECT_FALSE(std::filesystem::exists(partial));
  EXPECT_FALSE(std::filesystem::exists(Options().store_root / "same.wbk"));
  EXPECT_TRUE(plan(r).ok());  // the name is free again
}

}  // namespace
}  // namespace wavebake

namespace wavebake {
namespace {

// Input from a remote client never names a file of the server: an update's
// old store is a path, so only the embedded bake (local_updates) plans one,
// and nothing is reserved for a refused request.
TEST_F(JobPlannerTest, AnUpdateFromAClientIsRefusedBeforeAnyFileIsRead) {
  v1::BakeRequest r = testing::BuiltinRequest("builtin:sphere-plane");
  r.set_light_res(8);
  r.set_layout("camera:16x16");
  r.set_update_from("/etc/passwd");
  absl::StatusOr<PlannedJob> remote = MakeJobPlanner(Options())(Request(r, "up.wbk"));
  ASSERT_FALSE(remote.ok());
  EXPECT_EQ(remote.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(remote.status().message()), ::testing::StartsWith("update_from: "));
  EXPECT_THAT(std::string(remote.status().message()),
              ::testing::Not(::testing::HasSubstr("passwd")));
  EXPECT_FALSE(std::filesystem::exists(Options().store_root / ".up.wbk.partial"));
}

}  // namespace
}  // namespace wavebake
