// Bakes with diffuse bounces through the whole embedded pipeline
// (core/transport/bounce_gather.h applied by TRANSFORM_COLUMNS): the spherical cavity
// relit under L ≡ 1 against its closed form on mesh, lightmap and camera
// layouts, stores bit-identical across 1, 2 and 3 workers, the .zattrs
// record, and the refusal.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "driver/bake/embedded_bake.h"
#include "runtime/env/env_map.h"
#include "runtime/relight/store_relight.h"
#include "storage/files/json_file.h"
#include "storage/store/store_reader.h"
#include "tests/testing/bowl_scene.h"
#include "tests/testing/file_tree.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake::driver {
namespace {

using test_support::ReadTree;
using test_support::ScratchDir;
using ::testing::HasSubstr;

// 20 rings × 40 segments: 801 vertices on a 32×32 hilbert grid, N = 8.
BakeParams BowlJob(int bounces) {
  BakeParams p;
  p.light_res = 8;
  p.supersample = 16;
  p.layout = "hilbert:32x32";
  p.tile_size = 8;
  p.column_group = 128;
  p.target_error = 0.002;
  p.bounces = bounces;
  p.gather_rays = 100;
  return p;
}

absl::Status Bake(const std::string& scene, const BakeParams& p, const std::filesystem::path& out,
                  int workers) {
  absl::StatusOr<v1::Job> job = EmbeddedBake(scene, p, out, {.workers = workers});
  if (!job.ok()) return job.status();
  if (job->phase() != v1::PHASE_DONE)
    return absl::InternalError(absl::StrCat("job ended ", job->phase(), ": ", job->error()));
  return absl::OkStatus();
}

// Mean over the samples of B(x)/ρ(x) relit under L ≡ 1 with every term.
double MeanUnderUniformLight(const std::filesystem::path& store) {
  absl::StatusOr<OpenedStore> opened = OpenStore(store);
  EXPECT_TRUE(opened.ok()) << opened.status();
  absl::StatusOr<EnvMap> env = LoadEnvMap("builtin:constant");
  EXPECT_TRUE(env.ok());
  absl::StatusOr<std::vector<float>> rgb = RelightImage(*opened, *env, opened->info.columns);
  EXPECT_TRUE(rgb.ok()) << rgb.status();
  double sum = 0;
  int n = 0;
  for (int c = 0; c < opened->samples.cells(); ++c) {
    const int32_t s = opened->samples.grid[c];
    if (s < 0) continue;
    sum += (*rgb)[3 * c] / opened->samples.albedo[s].x;
    ++n;
  }
  return sum / n;
}

TEST(BounceBakeTest, CavityMatchesTheGeometricSeriesAndWorkersAgree) {
  ScratchDir dir("bounce");
  const float a = 0.8f;
  const std::string scene = test_support::WriteBowlScene(dir.path(), 20, 40, a).string();

  ASSERT_TRUE(Bake(scene, BowlJob(0), dir.path() / "b0.wbk", 2).ok());
  ASSERT_TRUE(Bake(scene, BowlJob(2), dir.path() / "b2.wbk", 1).ok());
  const double direct = MeanUnderUniformLight(dir.path() / "b0.wbk");
  const double bounced = MeanUnderUniformLight(dir.path() / "b2.wbk");
  EXPECT_NEAR(direct, test_support::BowlSeries(a, 0), 0.01 * test_support::BowlSeries(a, 0));
  EXPECT_NEAR(bounced, test_support::BowlSeries(a, 2), 0.01 * test_support::BowlSeries(a, 2));

  // The record: two bounces, Σ T_b² for each, decreasing (a(1 − f) = 0.4).
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(dir.path() / "b2.wbk");
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->params.bounces, 2);
  const nlohmann::json& record = info->attrs.at("bounces");
  EXPECT_EQ(record.at("count"), 2);
  EXPECT_EQ(record.at("gather_rays"), 100);
  ASSERT_EQ(record.at("energy").size(), 3u);
  const double e0 = record["energy"][0], e1 = record["energy"][1], e2 = record["energy"][2];
  EXPECT_GT(e1, 0);
  EXPECT_LT(e1, e0);
  EXPECT_LT(e2, e1);
  // A 0-bounce store says nothing of bounces (its bytes are those of before).
  absl::StatusOr<StoreInfo> info0 = ReadStoreInfo(dir.path() / "b0.wbk");
  ASSERT_TRUE(info0.ok());
  EXPECT_FALSE(info0->attrs.contains("bounces"));
  EXPECT_FALSE(info0->attrs.at("params").contains("bounces"));

  // Bit-identical on any number of workers.
  const auto expected = ReadTree(dir.path() / "b2.wbk");
  for (int workers : {2, 3}) {
    const std::filesystem::path out = dir.path() / absl::StrCat("w", workers, ".wbk");
    ASSERT_TRUE(Bake(scene, BowlJob(2), out, workers).ok());
    EXPECT_TRUE(ReadTree(out) == expected) << workers << " workers";
  }
}

// The same cavity as a lightmap: bounces read the previous one bilinearly
// from the texels around each hit's texture coordinate.
TEST(BounceBakeTest, CavityLightmapMatchesTheGeometricSeries) {
  ScratchDir dir("bounce_uv");
  const float a = 0.8f;
  const std::string scene = test_support::WriteBowlScene(dir.path(), 20, 40, a).string();
  BakeParams p = BowlJob(2);
  p.layout = "uv:32x32";
  ASSERT_TRUE(Bake(scene, p, dir.path() / "uv.wbk", 2).ok());
  const double expected = test_support::BowlSeries(a, 2);
  EXPECT_NEAR(MeanUnderUniformLight(dir.path() / "uv.wbk"), expected, 0.01 * expected);
}

// The cavity seen by a camera: its pixels gather from the bowl's vertices,
// an auxiliary set baked as tiles of their own (core/bake/bake_gather.h);
// the store is bit-identical across worker counts and records the set.
TEST(BounceBakeTest, CameraGathersFromTheVerticesAndWorkersAgree) {
  ScratchDir dir("bounce_camera");
  const float a = 0.8f;
  const std::string scene = test_support::WriteBowlScene(dir.path(), 20, 40, a).string();
  BakeParams p = BowlJob(2);
  p.layout = "camera:16x16";
  ASSERT_TRUE(Bake(scene, p, dir.path() / "c1.wbk", 1).ok());
  const double expected = test_support::BowlSeries(a, 2);
  EXPECT_NEAR(MeanUnderUniformLight(dir.path() / "c1.wbk"), expected, 0.01 * expected);
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(dir.path() / "c1.wbk");
  ASSERT_TRUE(info.ok());
  const nlohmann::json& aux = info->attrs.at("bounces").at("auxiliary");
  EXPECT_EQ(aux.at("samples"), 801);
  EXPECT_EQ(aux.at("kind"), "vertices");
  // The record holds the vertices' bounces that the pixels gather, b < B
  // (G_aa^B A₀ is never formed): two energies, decreasing (a(1 − f) = 0.4).
  const nlohmann::json& energy = info->attrs.at("bounces").at("energy");
  ASSERT_EQ(energy.size(), 2u);
  EXPECT_GT(energy[1].get<double>(), 0);
  EXPECT_LT(energy[1].get<double>(), energy[0].get<double>());
  ASSERT_TRUE(Bake(scene, p, dir.path() / "c3.wbk", 3).ok());
  EXPECT_TRUE(ReadTree(dir.path() / "c3.wbk") == ReadTree(dir.path() / "c1.wbk"));
}

TEST(BounceBakeTest, RefusesAVisibilityTransport) {
  ScratchDir dir("bounce_refusal");
  BakeParams visibility = BowlJob(1);
  visibility.transport = Transport::kVisibility;
  visibility.refine = false;
  absl::StatusOr<v1::Job> job =
      EmbeddedBake("builtin:cubes-wall", visibility, dir.path() / "v.wbk", {.workers = 1});
  ASSERT_FALSE(job.ok());
  EXPECT_THAT(job.status().message(), HasSubstr("triple product"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "v.wbk"));
}

}  // namespace
}  // namespace wavebake::driver
