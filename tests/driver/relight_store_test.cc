// The runtime against real stores baked by the embedded bake
// (driver/bake/embedded_bake.h): the white furnace through bake + relight, the
// compressed path against the dense retrace of the same T, `eval`'s report,
// RelightToFile outputs, and bad inputs. Lives in tests/driver because the
// driver is the layer that links both the bake and the runtime.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/bake/bake_params.h"
#include "driver/bake/embedded_bake.h"
#include "driver/eval/evaluate.h"
#include "driver/relight/relight_sequence.h"
#include "driver/relight/relight_to_file.h"
#include "runtime/env/env_resample.h"
#include "runtime/reference/dense_trace.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/store_relight.h"
#include "storage/scene_files/scene_loader.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake::driver {
namespace {

using TempDir = test_support::ScratchDir;

BakeParams SmallBake(const std::string& layout = "camera:32x32") {
  BakeParams p;
  p.light_res = 8;
  p.layout = layout;
  p.tile_size = 16;
  p.column_group = 128;
  return p;
}

std::filesystem::path Bake(const TempDir& dir, const std::string& name, const char* scene,
                           const BakeParams& p) {
  const auto out = dir.path() / name;
  absl::StatusOr<v1::Job> job = driver::EmbeddedBake(scene, p, out, {.workers = 2});
  EXPECT_TRUE(job.ok()) << job.status();
  if (job.ok()) {
    EXPECT_EQ(job->phase(), v1::PHASE_DONE) << job->error();
  }
  return out;
}

// DESIGN.md §1 white furnace through the whole pipeline: bake, quantize,
// store, read, Eq. 8 — L ≡ 1 relights every sample to its albedo.
TEST(RelightStore, WhiteFurnace) {
  TempDir dir;
  const auto store = Bake(dir, "furnace.wbk", "builtin:furnace", SmallBake());
  auto opened = OpenStore(store);
  ASSERT_TRUE(opened.ok()) << opened.status();
  auto env = LoadEnvMap("builtin:constant");
  ASSERT_TRUE(env.ok());
  auto rgb = RelightImage(*opened, *env, 64);
  ASSERT_TRUE(rgb.ok()) << rgb.status();
  const SampleSet& s = opened->samples;
  int checked = 0;
  for (int cell = 0; cell < s.cells(); ++cell) {
    const int32_t id = s.grid[cell];
    if (id < 0) {
      EXPECT_TRUE(std::isnan((*rgb)[3 * cell]));
      continue;
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR((*rgb)[3 * cell + c] / s.albedo[id][c], 1, 0.01);
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

// The store's relighting against T·L with T retraced exactly as the bake did
// (runtime/reference/dense_trace.h, brute force with the same jitter seed): with every
// light and 16-bit quantization only the column compression (target 1 %) is
// left; with fewer lights the error grows.
TEST(RelightStore, CompressedMatchesDenseRetrace) {
  TempDir dir;
  BakeParams p = SmallBake();
  p.bits = 16;
  p.refine = false;  // the dense retrace is brute force
  const auto store = Bake(dir, "disk.wbk", "builtin:disk-over-plane", p);
  auto opened = OpenStore(store);
  ASSERT_TRUE(opened.ok()) << opened.status();
  auto scene = LoadScene(opened->info.scene_spec);
  ASSERT_TRUE(scene.ok());
  auto caster = RayCaster::Build(*scene);
  ASSERT_TRUE(caster.ok());
  for (const char* spec : {"builtin:sky", WB_SHARED_DATA "/probes/grace.hdr"}) {
    auto env = LoadEnvMap(spec);
    ASSERT_TRUE(env.ok());
    const std::vector<float> cube = ResampleToCubemap(*env, Cubemap(8));
    auto dense = TraceDenseRelight(*caster, opened->samples, cube,
                                   {8, p.supersample, p.seed, p.ray_epsilon});
    ASSERT_TRUE(dense.ok());
    double previous = 1e9;
    for (int terms : {4, 16, 64, 384}) {
      auto rgb = RelightImage(*opened, *env, terms);
      ASSERT_TRUE(rgb.ok());
      const double err = CompareToReference(*rgb, dense->rgb).rel_rms;
      std::printf("%s terms %3d: rel_rms vs dense %.5f\n", spec, terms, err);
      EXPECT_LE(err, previous * 1.0001 + 1e-6);
      previous = err;
    }
    EXPECT_LT(previous, 0.01) << spec;
  }
}

// eval end to end on a small store: the JSON of DESIGN.md §5, a reference
// within its 0.2 % target, and the expected ordering of the errors.
TEST(RelightStore, EvalReport) {
  TempDir dir;
  const auto store = Bake(dir, "disk.wbk", "builtin:disk-over-plane", SmallBake("camera:16x16"));
  const std::string grace = WB_SHARED_DATA "/probes/grace.hdr";
  auto few = Evaluate(store, grace, 8);
  ASSERT_TRUE(few.ok()) << few.status();
  auto all = Evaluate(store, grace, 384);
  ASSERT_TRUE(all.ok()) << all.status();
  const nlohmann::json j = EvalReportJson(*all);
  std::printf("%s\n", j.dump().c_str());
  for (const char* part : {"dense", "compressed"}) {
    for (const char* key : {"rel_rms", "max_abs", "psnr", "seconds"}) {
      EXPECT_TRUE(j[part].contains(key)) << part << "." << key;
    }
  }
  EXPECT_EQ(j["terms"], 384);
  EXPECT_LE(all->reference_rel_se, 0.002);
  EXPECT_TRUE(all->reference_converged);
  // The same reference (same seed) for both runs, and the dense answer does
  // not depend on the terms.
  EXPECT_EQ(few->dense.rel_rms, all->dense.rel_rms);
  EXPECT_GT(few->compressed.rel_rms, all->compressed.rel_rms);
  EXPECT_LT(all->compressed.rel_rms, all->dense.rel_rms + 0.01);
  EXPECT_GT(all->compressed.psnr, few->compressed.psnr);
}

TEST(RelightStore, RelightToFileWritesImagesAndMeshes) {
  TempDir dir;
  const auto camera = Bake(dir, "cam.wbk", "builtin:sphere-plane", SmallBake("camera:16x16"));
  const auto png = dir.path() / "out.png", exr = dir.path() / "out.exr";
  ASSERT_TRUE(RelightToFile(camera, "builtin:sky", 32, 30, 0, png).ok());
  ASSERT_TRUE(RelightToFile(camera, "builtin:sky", 32, 0, 0, exr).ok());
  EXPECT_GT(std::filesystem::file_size(png), 8u);
  EXPECT_GT(std::filesystem::file_size(exr), 8u);
  const absl::Status ply_on_camera =
      RelightToFile(camera, "builtin:sky", 32, 0, 0, dir.path() / "x.ply");
  EXPECT_EQ(ply_on_camera.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(ply_on_camera.message().find("out"), std::string_view::npos) << ply_on_camera;

  const auto grid = Bake(dir, "grid.wbk", "builtin:disk-over-plane", SmallBake("grid"));
  const auto ply = dir.path() / "mesh.ply";
  ASSERT_TRUE(RelightToFile(grid, "builtin:sky", 32, 0, 0, ply).ok());
  std::ifstream in(ply, std::ios::binary);
  std::string header((std::istreambuf_iterator<char>(in)), {});
  auto scene = LoadScene("builtin:disk-over-plane");
  ASSERT_TRUE(scene.ok());
  size_t vertices = 0;
  for (const Mesh& m : scene->meshes) vertices += m.positions.size();
  EXPECT_NE(header.find("element vertex " + std::to_string(vertices)), std::string::npos);
}

TEST(RelightStore, BadInputsGiveClearErrors) {
  TempDir dir;
  const auto store = Bake(dir, "s.wbk", "builtin:furnace", SmallBake("camera:16x16"));
  auto expect = [](const absl::Status& s, const char* word) {
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message().find(word), std::string_view::npos) << s;
  };
  expect(Evaluate(store, "builtin:constant", 0).status(), "terms");
  expect(Evaluate(store, "builtin:constant", -3).status(), "terms");
  expect(RelightToFile(store, "builtin:constant", 0, 0, 0, dir.path() / "a.png"), "terms");
  expect(RelightToFile(store, "builtin:constant", 8, 0, 0, dir.path() / "a.bmp"), "out");
  expect(RelightToFile(store, "builtin:constant", 8, NAN, 0, dir.path() / "a.png"), "rotate");
  expect(RelightToFile(store, dir.path().string() + "/none.hdr", 8, 0, 0, dir.path() / "a.png"),
         "none.hdr");
  expect(Evaluate(dir.path() / "missing.wbk", "builtin:constant", 8).status(), "missing.wbk");

  // A store of another format version: rewrite the root attrs' "format".
  const auto attrs_path = store / ".zattrs";
  std::ifstream in(attrs_path);
  nlohmann::json attrs = nlohmann::json::parse(in);
  in.close();
  attrs["format"] = "wavebake/0";
  std::ofstream(attrs_path) << attrs.dump();
  expect(OpenStore(store).status(), "format");
  expect(Evaluate(store, "builtin:constant", 8).status(), "format");
}

// `relight --rotate-sequence` with START == END is static lighting: per-band
// (Overbeck §6.2.2) and basic (ch. 4) incremental relighting keep moving n
// more residual terms into their approximation, so their error against the
// all-lights image falls to ~0, while the non-incremental error stays at the
// n-term truncation error of frame 0 (which they equal: all start from L̃ = 0).
TEST(RelightSequence, StaticLightingConvergesOnlyIncrementally) {
  TempDir dir;
  const auto store = Bake(dir, "seq.wbk", "builtin:cubes-wall", SmallBake());
  SequenceOptions o{.rotation = {.start_degrees = 30, .end_degrees = 30, .frames = 40},
                    .terms = 16,
                    .out_dir = dir.path() / "frames"};
  auto per_band = RelightSequence(store, "builtin:sky", o);
  ASSERT_TRUE(per_band.ok()) << per_band.status();
  o.mode = SequenceMode::kNonIncremental;
  o.out_dir.clear();
  auto plain = RelightSequence(store, "builtin:sky", o);
  ASSERT_TRUE(plain.ok()) << plain.status();
  ASSERT_EQ(per_band->size(), 40u);
  EXPECT_GT(plain->front().rel_rms, 1e-3) << "16 terms should not be exact";
  EXPECT_NEAR(per_band->front().rel_rms, plain->front().rel_rms, 1e-6);
  for (const SequenceFrame& f : *plain) EXPECT_NEAR(f.rel_rms, plain->front().rel_rms, 1e-6);
  EXPECT_LT(per_band->back().rel_rms, 1e-4);
  o.mode = SequenceMode::kBasic;
  o.rotation.frames = 26;  // M = 384 terms, 16 per frame: exact from frame 25 on
  auto basic = RelightSequence(store, "builtin:sky", o);
  ASSERT_TRUE(basic.ok()) << basic.status();
  EXPECT_NEAR(basic->front().rel_rms, plain->front().rel_rms, 1e-6);
  EXPECT_LT(basic->back().rel_rms, 1e-4);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "frames" / "frame_0039.png"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "frames" / "errors.csv"));
}

TEST(RelightSequence, BadSpecsNameTheFlag) {
  for (const char* spec : {"0:90", "a:90:10", "0:90:0", "0:inf:10", "0:90:10:1"}) {
    auto r = ParseRotateSequence(spec);
    ASSERT_FALSE(r.ok()) << spec;
    EXPECT_THAT(std::string(r.status().message()), testing::HasSubstr("rotate-sequence")) << spec;
  }
  auto r = ParseRotateSequence("-45:45.5:7");
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_EQ(r->frames, 7);
  EXPECT_DOUBLE_EQ(r->end_degrees, 45.5);
}

}  // namespace
}  // namespace wavebake::driver
