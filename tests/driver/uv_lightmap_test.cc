// The lightmap workflow end to end (DESIGN.md §1 "Spatial layout" uv, §5
// relight): a UV-mapped quad baked on the uv layout and relit. Anchors: the
// white furnace (L ≡ 1, nothing occluding: every texel is the albedo), and
// the gutters of the written PNG, which must hold a nearest chart texel's
// value (what bilinear sampling near a chart border reads).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>

#include "driver/bake/embedded_bake.h"
#include "runtime/env/env_map.h"
#include "runtime/io/lightmap.h"
#include "runtime/io/stb_codecs.h"
#include "runtime/relight/store_relight.h"
#include "storage/files/atomic_file.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake {
namespace {

using test_support::ScratchDir;

constexpr int kSide = 32;

// The unit quad z = 0 facing +z, UVs [0.3, 0.7]²: texels 9..22 of 32² are
// covered, 9.6 to 22.4 in texel units.
std::filesystem::path WriteQuadObj(const std::filesystem::path& dir) {
  const std::filesystem::path obj = dir / "quad.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                        "vt 0.3 0.3\nvt 0.7 0.3\nvt 0.7 0.7\nvt 0.3 0.7\n"
                        "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
  return obj;
}

class UvLightmapTest : public ::testing::Test {
 protected:
  // A failed bake fails every test (an ASSERT here would only skip them).
  static void SetUpTestSuite() {
    dir_ = std::make_unique<ScratchDir>("uv_lightmap");
    BakeParams p;
    p.light_res = 8;
    p.layout = "uv:32x32";
    p.tile_size = 16;
    p.column_group = 128;
    store_ = dir_->path() / "quad.wbk";
    const absl::StatusOr<v1::Job> job =
        driver::EmbeddedBake(WriteQuadObj(dir_->path()).string(), p, store_, {.workers = 2});
    if (!job.ok()) setup_error_ = job.status().ToString();
    if (job.ok() && job->phase() != v1::PHASE_DONE) setup_error_ = job->error();
  }
  static void TearDownTestSuite() { dir_.reset(); }
  void SetUp() override { ASSERT_EQ(setup_error_, "") << "the suite's bake failed"; }

  static inline std::unique_ptr<ScratchDir> dir_;
  static inline std::string setup_error_;
  static inline std::filesystem::path store_;
};

bool Covered(int x, int y) { return x >= 9 && x <= 22 && y >= 9 && y <= 22; }

TEST_F(UvLightmapTest, WhiteFurnaceGivesTheAlbedoInEveryCoveredTexel) {
  absl::StatusOr<OpenedStore> store = OpenStore(store_);
  ASSERT_TRUE(store.ok()) << store.status();
  ASSERT_EQ(store->samples.size(), 14 * 14);
  const absl::StatusOr<EnvMap> env = LoadEnvMap("builtin:constant");
  ASSERT_TRUE(env.ok());
  const absl::StatusOr<std::vector<float>> rgb = RelightImage(*store, *env, 6 * 8 * 8);
  ASSERT_TRUE(rgb.ok()) << rgb.status();
  // ∫ over the upper hemisphere of cos/π = 1, so B = albedo (the OBJ has no
  // material: 0.8), up to the N = 8 cubemap's discretization and the 1 % target.
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = (*rgb)[3 * (y * kSide + x) + c];
        if (Covered(x, y)) {
          EXPECT_NEAR(v, 0.8f, 0.8f * 0.03f) << x << "," << y;
        } else {
          EXPECT_TRUE(std::isnan(v)) << x << "," << y;
        }
      }
}

TEST_F(UvLightmapTest, PngGutterHoldsTheNearestChartTexel) {
  absl::StatusOr<OpenedStore> store = OpenStore(store_);
  ASSERT_TRUE(store.ok()) << store.status();
  // A lightmap that differs from texel to texel (so that "nearest" is
  // visible), NaN off the chart as a relit image is.
  std::vector<float> rgb(3 * kSide * kSide, NAN);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      if (Covered(x, y))
        for (int c = 0; c < 3; ++c)
          rgb[3 * (y * kSide + x) + c] = ((x * 7 + y * 3 + c) % 11) / 11.0f;
  const std::filesystem::path png = dir_->path() / "lightmap.png";
  ASSERT_TRUE(WriteRelit(*store, rgb, 0, png).ok());
  absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(png);
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  absl::StatusOr<Rgb8Image> image = DecodePng(*bytes, png.string());
  ASSERT_TRUE(image.ok()) << image.status();
  ASSERT_EQ(image->width, kSide);
  ASSERT_EQ(image->height, kSide);
  auto at = [&](int x, int y, int c) { return image->rgb[3 * (y * kSide + x) + c]; };
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      if (Covered(x, y)) continue;
      // Chebyshev distance to the chart 9..22 and the chart texels at it.
      const int cx = std::clamp(x, 9, 22), cy = std::clamp(y, 9, 22);
      const int d = std::max(std::abs(x - cx), std::abs(y - cy));
      if (d > kLightmapGutter) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(at(x, y, c), 0) << x << "," << y;
        continue;
      }
      bool matches = false;
      for (int sy = 9; sy <= 22; ++sy)
        for (int sx = 9; sx <= 22; ++sx) {
          if (std::max(std::abs(x - sx), std::abs(y - sy)) != d) continue;
          matches = matches || (at(x, y, 0) == at(sx, sy, 0) && at(x, y, 1) == at(sx, sy, 1) &&
                                at(x, y, 2) == at(sx, sy, 2));
        }
      EXPECT_TRUE(matches) << "gutter texel " << x << "," << y << " at distance " << d;
    }
}

TEST_F(UvLightmapTest, PlyIsRefusedForALightmap) {
  absl::StatusOr<OpenedStore> store = OpenStore(store_);
  ASSERT_TRUE(store.ok());
  const std::vector<float> rgb(3 * kSide * kSide, 0.5f);
  const absl::Status s = WriteRelit(*store, rgb, 0, dir_->path() / "x.ply");
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find(".png or .exr"), std::string::npos) << s;
}

}  // namespace
}  // namespace wavebake
