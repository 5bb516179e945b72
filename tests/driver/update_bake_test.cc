// `bake NEW --update OLD.wbk` (worker/tiles/row_reuse.h): with --update-exact the
// store is byte-identical to a full bake of the new scene (every file; the
// .zattrs too once its "update" record is set aside), for a camera and a
// hilbert layout (which re-sorts its samples when a mesh moves); an
// unchanged scene rebakes no row; and an update the old store cannot seed
// is refused naming why, leaving the old store as it was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "driver/bake/embedded_bake.h"
#include "storage/files/atomic_file.h"
#include "storage/zarr/zarr_array.h"
#include "storage/zarr/zstd_codec.h"
#include "tests/testing/file_tree.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake::driver {
namespace {

using test_support::ReadTree;
using test_support::ScratchDir;
using ::testing::HasSubstr;

// An n×n grid of the square [-1, 1]² at y = 0, facing +y (OBJ).
void WriteGround(const std::filesystem::path& path, int n) {
  std::ofstream f(path);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      f << "v " << -1 + 2.0 * i / (n - 1) << " 0 " << -1 + 2.0 * j / (n - 1) << "\n";
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i + 1, b = a + 1, c = a + n, d = c + 1;
      f << "f " << a << " " << c << " " << b << "\nf " << b << " " << c << " " << d << "\n";
    }
}

// A closed unit cube [-0.5, 0.5]³ (outward faces).
void WriteCube(const std::filesystem::path& path) {
  std::ofstream f(path);
  for (int k = 0; k < 8; ++k)
    f << "v " << ((k & 1) ? 0.5 : -0.5) << " " << ((k & 2) ? 0.5 : -0.5) << " "
      << ((k & 4) ? 0.5 : -0.5) << "\n";
  f << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
}

// Ground, a tall block at the back (it fixes the bounding box, hence ε) and
// a small box whose foot is at (x, z).
void WriteScene(const std::filesystem::path& path, double x, double z, double red = 0.8) {
  const nlohmann::json scene = {
      {"meshes",
       {{{"file", "ground.obj"}},
        {{"file", "cube.obj"},
         {"transform", {{"scale", {1.6, 0.8, 0.2}}, {"translate", {0, 0.4, -0.85}}}}},
        {{"file", "cube.obj"},
         {"albedo", {red, 0.8, 0.8}},
         {"transform", {{"scale", 0.15}, {"translate", {x, 0.075, z}}}}}}},
      {"camera", {{"eye", {0, 1.6, 2.2}}, {"target", {0, 0.1, 0}}}}};
  std::ofstream(path) << scene.dump(2);
}

class UpdateBakeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    WriteGround(dir_.path() / "ground.obj", 9);
    WriteCube(dir_.path() / "cube.obj");
    WriteScene(old_scene_, -0.5, 0.3);
    WriteScene(new_scene_, 0.45, 0.35);
  }
  BakeParams Params(const std::string& layout) const {
    BakeParams p;
    p.light_res = 8;
    p.layout = layout;
    p.tile_size = 8;
    p.column_group = 128;
    p.keep_staging = true;
    return p;
  }
  absl::StatusOr<v1::Job> Bake(const std::filesystem::path& scene, const BakeParams& p,
                               const std::filesystem::path& out) {
    absl::StatusOr<v1::Job> job = EmbeddedBake(scene.string(), p, out, {.workers = 2});
    if (job.ok() && job->phase() != v1::PHASE_DONE)
      return absl::InternalError(absl::StrCat("job ended ", job->phase(), ": ", job->error()));
    return job;
  }
  // The update's store against a full bake: equal bytes in every file, and
  // .zattrs equal once "update" is dropped. Returns the record.
  nlohmann::json ExpectSameAsFullBake(const std::filesystem::path& updated,
                                      const std::filesystem::path& full) {
    auto a = ReadTree(updated), b = ReadTree(full);
    EXPECT_TRUE(a.contains(".zattrs"));
    nlohmann::json attrs_a = nlohmann::json::parse(a[".zattrs"]);
    const nlohmann::json attrs_b = nlohmann::json::parse(b[".zattrs"]);
    const nlohmann::json record = attrs_a["update"];
    attrs_a.erase("update");
    EXPECT_EQ(attrs_a, attrs_b);
    a.erase(".zattrs");
    b.erase(".zattrs");
    EXPECT_EQ(a.size(), b.size());
    for (const auto& [name, bytes] : b) EXPECT_TRUE(a[name] == bytes) << name << " differs";
    return record;
  }

  ScratchDir dir_{"update"};
  const std::filesystem::path old_scene_ = dir_.path() / "old.json",
                              new_scene_ = dir_.path() / "new.json";
};

TEST_F(UpdateBakeTest, ExactUpdateIsByteIdenticalToAFullBake) {
  for (const std::string layout : {"camera:16x16", "hilbert:16x16"}) {
    SCOPED_TRACE(layout);
    const auto old_store = dir_.path() / "old.wbk", full = dir_.path() / "full.wbk",
               updated = dir_.path() / "updated.wbk";
    ASSERT_TRUE(Bake(old_scene_, Params(layout), old_store).ok());
    ASSERT_TRUE(Bake(new_scene_, Params(layout), full).ok());
    BakeParams p = Params(layout);
    p.update_from = old_store.string();
    p.update_exact = true;
    ASSERT_TRUE(Bake(new_scene_, p, updated).ok());
    const nlohmann::json record = ExpectSameAsFullBake(updated, full);
    EXPECT_EQ(record.value("mode", ""), "exact");
    // The small box moved: some rows are rebaked, and the block hides some from it.
    EXPECT_GT(record.value("rows_rebaked", 0), 0) << record.dump();
    EXPECT_GT(record.value("rows_reused", 0), 0) << record.dump();
    EXPECT_EQ(record.value("rows_reused", 0) + record.value("rows_rebaked", 0),
              record.value("rows", -1));
    EXPECT_THAT(record["changed_meshes"].dump(), HasSubstr("cube"));
    for (const auto& s : {old_store, full, updated}) std::filesystem::remove_all(s);
  }
}

TEST_F(UpdateBakeTest, UnchangedSceneRebakesNoRow) {
  const auto old_store = dir_.path() / "old.wbk", again = dir_.path() / "again.wbk";
  ASSERT_TRUE(Bake(old_scene_, Params("camera:16x16"), old_store).ok());
  BakeParams p = Params("camera:16x16");
  p.update_from = old_store.string();
  ASSERT_TRUE(Bake(old_scene_, p, again).ok());
  // --update (local columns) keeps every old coded column: the old store's bytes.
  const nlohmann::json record = ExpectSameAsFullBake(again, old_store);
  EXPECT_EQ(record.value("rows_rebaked", -1), 0) << record.dump();
  EXPECT_EQ(record.value("columns_recomputed", -1), 0) << record.dump();
}

// A repainted box changes no row (albedo is factored out of T): the update
// runs the pipeline, reuses every row, recodes no column, and its store is
// the full bake's of the repainted scene (new samples/albedo).
TEST_F(UpdateBakeTest, AlbedoEditReusesEveryRowAndColumn) {
  const auto painted = dir_.path() / "painted.json";
  WriteScene(painted, -0.5, 0.3, 0.2);
  const auto old_store = dir_.path() / "old.wbk", full = dir_.path() / "full.wbk",
             updated = dir_.path() / "updated.wbk";
  ASSERT_TRUE(Bake(old_scene_, Params("hilbert:16x16"), old_store).ok());
  ASSERT_TRUE(Bake(painted, Params("hilbert:16x16"), full).ok());
  BakeParams p = Params("hilbert:16x16");
  p.update_from = old_store.string();
  ASSERT_TRUE(Bake(painted, p, updated).ok());
  const nlohmann::json record = ExpectSameAsFullBake(updated, full);
  EXPECT_EQ(record.value("rows_reused", -1), record.value("rows", -2)) << record.dump();
  EXPECT_EQ(record.value("columns_recomputed", -1), 0) << record.dump();
  EXPECT_THAT(record["albedo_meshes"].dump(), HasSubstr("cube"));
}

// A hilbert layout keeps the old cells (the moved box's vertices stay in
// theirs), so its columns are kept as a camera layout's are.
TEST_F(UpdateBakeTest, LocalUpdateRecomputesOnlyChangedColumns) {
  for (const std::string layout : {"camera:16x16", "hilbert:16x16"}) {
    SCOPED_TRACE(layout);
    const auto old_store = dir_.path() / "old.wbk", updated = dir_.path() / "updated.wbk";
    ASSERT_TRUE(Bake(old_scene_, Params(layout), old_store).ok());
    BakeParams p = Params(layout);
    p.update_from = old_store.string();
    ASSERT_TRUE(Bake(new_scene_, p, updated).ok());
    const nlohmann::json attrs = nlohmann::json::parse(ReadTree(updated).at(".zattrs"));
    const nlohmann::json& u = attrs["update"];
    EXPECT_EQ(u.value("mode", ""), "local");
    EXPECT_EQ(u.value("columns", 0), 6 * 8 * 8);
    EXPECT_GT(u.value("columns_recomputed", 0), 0) << u.dump();
    EXPECT_LT(u.value("columns_recomputed", 0), u.value("columns", 0)) << u.dump();
    // A recomputed column keeps its old depth unless it was searched again,
    // which few are: a small edit moves few columns' energy by a quarter.
    EXPECT_LT(u.value("columns_depth_searched", -1), u.value("columns_recomputed", 0));
    const auto depths = [](const std::filesystem::path& store) {
      absl::StatusOr<ZarrArray> a = ZarrArray::Open(store / "transport/depth");
      EXPECT_TRUE(a.ok()) << a.status();
      absl::StatusOr<std::vector<uint8_t>> d = a->ReadAll<uint8_t>();
      EXPECT_TRUE(d.ok()) << d.status();
      return *d;
    };
    const std::vector<uint8_t> was = depths(old_store), now = depths(updated);
    ASSERT_EQ(was.size(), now.size());
    int moved = 0;
    for (size_t m = 0; m < was.size(); ++m) moved += was[m] != now[m];
    EXPECT_LE(moved, u.value("columns_depth_searched", -1)) << u.dump();
    // Rows the moved box reaches through few texels are patched, not traced;
    // those with no old sample at their position (on the box, or where it
    // stood) and those that see it large are traced.
    EXPECT_GT(u.value("rows_patched", 0), 0) << u.dump();
    EXPECT_GE(u.value("rows_rebaked", -1), u.value("rows_unmatched", -2)) << u.dump();
    EXPECT_EQ(u.value("rows_reused", 0) + u.value("rows_patched", 0) + u.value("rows_rebaked", 0),
              u.value("rows", -1));
    for (const auto& s : {old_store, updated}) std::filesystem::remove_all(s);
  }
}

// A tile whose every row is an old row in its old cell stages the old
// chunks as they were encoded: planted with another encoding of the same
// values (zstd level 19), they reach the update's staging byte for byte,
// while the tiles the box touched are staged anew; the matrix is the full
// bake's either way.
TEST_F(UpdateBakeTest, UntouchedTilesCopyTheirStagedChunks) {
  const auto old_store = dir_.path() / "old.wbk", full = dir_.path() / "full.wbk",
             updated = dir_.path() / "updated.wbk";
  ASSERT_TRUE(Bake(old_scene_, Params("camera:32x32"), old_store).ok());
  ASSERT_TRUE(Bake(new_scene_, Params("camera:32x32"), full).ok());
  absl::StatusOr<ZarrArray> staged = ZarrArray::Open(old_store / "staging/transport");
  ASSERT_TRUE(staged.ok()) << staged.status();
  std::map<std::string, std::vector<std::byte>> planted;
  for (int64_t g = 0; g < staged->chunk_grid()[0]; ++g)
    for (int64_t t = 0; t < staged->chunk_grid()[1]; ++t) {
      const std::vector<int64_t> index{g, t};
      absl::StatusOr<std::vector<float>> values = staged->ReadChunk<float>(index);
      ASSERT_TRUE(values.ok()) << values.status();
      absl::StatusOr<std::vector<std::byte>> frame =
          ZstdCompress(std::as_bytes(std::span(*values)), 19);
      ASSERT_TRUE(frame.ok());
      ASSERT_TRUE(AtomicWriteFile(staged->ChunkPath(index), *frame).ok());
      planted[staged->ChunkPath(index).filename().string()] = *frame;
    }
  BakeParams p = Params("camera:32x32");
  p.update_from = old_store.string();
  p.update_exact = true;
  ASSERT_TRUE(Bake(new_scene_, p, updated).ok());

  const auto now = ReadTree(updated / "staging/transport"),
             baked = ReadTree(full / "staging/transport");
  int copied = 0, staged_anew = 0;
  for (const auto& [name, frame] : planted) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(now.contains(name));
    const std::string bytes(reinterpret_cast<const char*>(frame.data()), frame.size());
    copied += now.at(name) == bytes;
    staged_anew += now.at(name) == baked.at(name);
    EXPECT_TRUE(now.at(name) == bytes || now.at(name) == baked.at(name));
  }
  EXPECT_GT(copied, 0);
  EXPECT_GT(staged_anew, 0);
  EXPECT_TRUE(ReadTree(updated / "transport") == ReadTree(full / "transport"));
}

// With bounces an edit reaches every sample's bounced light (the gather
// spans the scene), so an update reuses direct rows only and codes every
// column from them and the new scene's gather. Exact, it is the full bake's
// store, camera (its auxiliary vertex rows) and hilbert alike; a repainted
// box changes no direct row but the light it bounces, and even --update
// then gives the full bake's bytes — which an update gathering with the old
// albedo, or keeping old columns, would not. (--update codes a column at its
// old depth when its energy moved little; here those are the depths the full
// bake's search finds.)
TEST_F(UpdateBakeTest, UpdatesWithBouncesRecodeEveryColumnFromTheNewGather) {
  const auto painted = dir_.path() / "painted.json";
  WriteScene(painted, -0.5, 0.3, 0.2);
  struct Case {
    std::string layout;
    std::filesystem::path scene;
    bool exact;
  };
  for (const Case& c :
       {Case{"camera:16x16", new_scene_, true}, Case{"hilbert:16x16", new_scene_, true},
        Case{"hilbert:16x16", painted, false}}) {
    SCOPED_TRACE(c.layout + " " + c.scene.filename().string());
    BakeParams p = Params(c.layout);
    p.bounces = 1;
    p.gather_rays = 64;
    const auto old_store = dir_.path() / "old.wbk", full = dir_.path() / "full.wbk",
               updated = dir_.path() / "updated.wbk";
    ASSERT_TRUE(Bake(old_scene_, p, old_store).ok());
    ASSERT_TRUE(Bake(c.scene, p, full).ok());
    p.update_from = old_store.string();
    p.update_exact = c.exact;
    ASSERT_TRUE(Bake(c.scene, p, updated).ok());
    const nlohmann::json record = ExpectSameAsFullBake(updated, full);
    EXPECT_EQ(record.value("bounces", -1), 1) << record.dump();
    EXPECT_EQ(record.value("columns_recomputed", -1), record.value("columns", -2));
    EXPECT_GT(record.value("rows_reused", 0), 0) << record.dump();
    for (const auto& s : {old_store, full, updated}) std::filesystem::remove_all(s);
  }
}

// A moved box with bounces: --update patches and reuses direct rows as
// without them, then codes every column. Its hilbert cells are its own, not
// the old store's: the gather was built over them (with the old cells the
// bounced light landed in the wrong cells, 1.2 % off in energy here). The
// matrix is the full bake's up to the patches' brute-force differences.
TEST_F(UpdateBakeTest, LocalUpdateWithBouncesIsCloseToTheFullBake) {
  BakeParams p = Params("hilbert:16x16");
  p.bounces = 1;
  p.gather_rays = 64;
  const auto old_store = dir_.path() / "old.wbk", full = dir_.path() / "full.wbk",
             updated = dir_.path() / "updated.wbk";
  ASSERT_TRUE(Bake(old_scene_, p, old_store).ok());
  ASSERT_TRUE(Bake(new_scene_, p, full).ok());
  p.update_from = old_store.string();
  ASSERT_TRUE(Bake(new_scene_, p, updated).ok());
  const nlohmann::json a = nlohmann::json::parse(ReadTree(updated).at(".zattrs")),
                       b = nlohmann::json::parse(ReadTree(full).at(".zattrs"));
  const nlohmann::json& u = a["update"];
  EXPECT_EQ(u.value("mode", ""), "local");
  EXPECT_EQ(u.value("columns_recomputed", -1), u.value("columns", -2)) << u.dump();
  // Most columns keep their old depth; their energy moved little.
  EXPECT_GE(u.value("columns_depth_searched", -1), 0) << u.dump();
  EXPECT_LT(u.value("columns_depth_searched", -1), u.value("columns", 0) / 2) << u.dump();
  EXPECT_GT(u.value("rows_reused", 0), 0) << u.dump();
  EXPECT_GT(u.value("rows_patched", 0), 0) << u.dump();
  EXPECT_TRUE(ReadTree(updated / "samples") == ReadTree(full / "samples"));  // the same cells
  const double e_update = a["stats"].value("energy", 0.0), e_full = b["stats"].value("energy", 1.0);
  EXPECT_GT(e_full, 0);
  EXPECT_NEAR(e_update / e_full, 1.0, 1e-3);
  // The bounce was gathered over the new scene in both.
  const nlohmann::json &bounced = a.at("bounces").at("energy"),
                       &full_bounced = b.at("bounces").at("energy");
  ASSERT_EQ(bounced.size(), 2u);
  EXPECT_GT(full_bounced[1].get<double>(), 0);
  EXPECT_NEAR(bounced[1].get<double>() / full_bounced[1].get<double>(), 1.0, 1e-3);
}

TEST_F(UpdateBakeTest, RefusalsNameWhyAndLeaveTheOldStore) {
  const auto old_store = dir_.path() / "old.wbk", plain = dir_.path() / "plain.wbk",
             out = dir_.path() / "out.wbk";
  ASSERT_TRUE(Bake(old_scene_, Params("camera:16x16"), old_store).ok());
  BakeParams no_staging = Params("camera:16x16");
  no_staging.keep_staging = false;
  ASSERT_TRUE(Bake(old_scene_, no_staging, plain).ok());
  const auto before = ReadTree(dir_.path());

  BakeParams p = Params("camera:16x16");
  p.update_from = plain.string();
  absl::StatusOr<v1::Job> job = Bake(new_scene_, p, out);
  EXPECT_EQ(job.status().code(), absl::StatusCode::kFailedPrecondition) << job.status();
  EXPECT_THAT(job.status().message(), HasSubstr("--keep-staging"));

  p = Params("camera:16x16");
  p.light_res = 16;
  p.update_from = old_store.string();
  job = Bake(new_scene_, p, out);
  EXPECT_THAT(job.status().message(), HasSubstr("parameter light_res is 8 there and 16 here"));

  p = Params("camera:16x16");
  p.update_from = (dir_.path() / "missing.wbk").string();
  job = Bake(new_scene_, p, out);
  EXPECT_THAT(job.status().message(), HasSubstr("--update needs a finished store"));

  // The old scene is gone, or edited since: refused before any task runs
  // (the status itself, not a job that failed), naming the scene.
  const auto moved = dir_.path() / "old.json.moved";
  std::filesystem::rename(old_scene_, moved);
  p = Params("camera:16x16");
  p.update_from = old_store.string();
  job = Bake(new_scene_, p, out);
  EXPECT_EQ(job.status().code(), absl::StatusCode::kFailedPrecondition) << job.status();
  EXPECT_THAT(job.status().message(), HasSubstr("its scene 'old.json'"));
  EXPECT_THAT(job.status().message(), HasSubstr("does not load"));
  std::filesystem::rename(moved, old_scene_);
  const std::string old_text = before.at("old.json");
  WriteScene(old_scene_, -0.4, 0.3);
  job = Bake(new_scene_, p, out);
  EXPECT_EQ(job.status().code(), absl::StatusCode::kFailedPrecondition) << job.status();
  EXPECT_THAT(job.status().message(), HasSubstr("has changed since the store was baked"));
  std::ofstream(old_scene_, std::ios::binary | std::ios::trunc) << old_text;

  // Also into the old store itself: refused before anything is written.
  p = Params("camera:16x16");
  p.target_error = 0.02;
  p.update_from = old_store.string();
  job = Bake(new_scene_, p, old_store);
  EXPECT_THAT(job.status().message(), HasSubstr("parameter target_error"));
  EXPECT_TRUE(ReadTree(dir_.path()) == before);
}

}  // namespace
}  // namespace wavebake::driver
