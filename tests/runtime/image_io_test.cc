// EXR, PNG and PLY writers: exact round trips, sizes, the sRGB encoding and
// atomic replacement.
#include "runtime/io/image_io.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include "env_test_util.h"
#include "gmock/gmock.h"
#include "runtime/io/stb_codecs.h"
#include "storage/files/atomic_file.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

TEST(ExrTest, FloatRoundTripIsBitExact) {
  const int w = 7, h = 5;  // odd sizes: no accidental symmetry
  std::vector<float> rgb(w * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = std::ldexp(1.0f + 0.37f * i, int(i % 40) - 20);
  rgb[4] = std::numeric_limits<float>::quiet_NaN();  // a masked pixel
  rgb[5] = 1e-40f;                                   // denormal
  const auto path = testing::ScratchDir() / "round.exr";
  ASSERT_TRUE(WriteExr(path, w, h, rgb).ok());
  const absl::StatusOr<EnvMap> back = ReadExrImage(path);
  ASSERT_TRUE(back.ok()) << back.status();
  ASSERT_EQ(back->width, w);
  ASSERT_EQ(back->height, h);
  ASSERT_EQ(back->rgb.size(), rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    EXPECT_EQ(std::bit_cast<uint32_t>(back->rgb[i]), std::bit_cast<uint32_t>(rgb[i])) << i;
  }
}

TEST(ExrTest, SizeMismatchAndMissingFileAreNamed) {
  const auto dir = testing::ScratchDir();
  std::vector<float> rgb(10);
  EXPECT_THAT(WriteExr(dir / "bad.exr", 2, 2, rgb).message(), HasSubstr("bad.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.exr"));
  EXPECT_EQ(ReadExrImage(dir / "none.exr").status().code(), absl::StatusCode::kNotFound);
}

struct Png {
  int w = 0, h = 0;
  std::vector<uint8_t> rgb;
};

Png ReadPng(const std::filesystem::path& path) {
  absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(path);
  if (!bytes.ok()) return {};
  absl::StatusOr<Rgb8Image> image = DecodePng(*bytes, path.string());
  if (!image.ok()) return {};
  return {image->width, image->height, image->rgb};
}

// sRGB OETF (IEC 61966-2-1): 1.055 c^(1/2.4) − 0.055 above 0.0031308.
TEST(PngTest, SizeExposureClampAndBackground) {
  const int w = 4, h = 3;
  std::vector<float> rgb(w * h * 3, 0.0f);
  rgb[0] = rgb[1] = rgb[2] = 0.25f;                  // pixel (0,0): ×2 at +1 stop → 0.5
  rgb[3] = 10.0f;                                    // pixel (1,0): clamps to 1
  rgb[6] = std::numeric_limits<float>::quiet_NaN();  // pixel (2,0): masked
  const auto path = testing::ScratchDir() / "out.png";
  ASSERT_TRUE(WritePng(path, w, h, rgb, 1.0f, {0, 0, 1}).ok());
  const Png png = ReadPng(path);
  ASSERT_EQ(png.w, w);
  ASSERT_EQ(png.h, h);
  const int half = static_cast<int>(std::lround(255 * (1.055 * std::pow(0.5, 1 / 2.4) - 0.055)));
  EXPECT_EQ(png.rgb[0], half);
  EXPECT_EQ(png.rgb[2], half);
  EXPECT_EQ(png.rgb[3], 255);
  EXPECT_EQ(png.rgb[4], 0);
  EXPECT_EQ(png.rgb[6], 0);
  EXPECT_EQ(png.rgb[7], 0);
  EXPECT_EQ(png.rgb[8], 255);
  EXPECT_EQ(png.rgb[w * h * 3 - 1], 0);
}

TEST(PngTest, ReplacesAtomicallyAndLeavesNoTemporaries) {
  const auto dir = testing::ScratchDir();
  const std::vector<float> grey(2 * 2 * 3, 0.18f), white(2 * 2 * 3, 1.0f);
  ASSERT_TRUE(WritePng(dir / "a.png", 2, 2, grey, 0, {}).ok());
  ASSERT_TRUE(WritePng(dir / "a.png", 2, 2, white, 0, {}).ok());
  EXPECT_EQ(ReadPng(dir / "a.png").rgb[0], 255);
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  const absl::Status s = WritePng(dir / "no/such/dir/a.png", 2, 2, grey, 0, {});
  EXPECT_FALSE(s.ok());
  EXPECT_THAT(s.message(), HasSubstr("no/such/dir/a.png"));
}

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(PlyTest, HeaderCountsAndBinaryBody) {
  Scene scene;
  Mesh a, b;
  a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  a.triangles = {{0, 1, 2}};
  b.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  b.triangles = {{0, 1, 2}, {1, 3, 2}};
  scene.meshes = {a, b};
  std::vector<float> rgb(7 * 3, 0.5f);
  const auto path = testing::ScratchDir() / "mesh.ply";
  ASSERT_TRUE(WritePlyVertexColors(path, scene, rgb, 0).ok());
  const std::string ply = ReadAll(path);
  EXPECT_THAT(ply, HasSubstr("format binary_little_endian 1.0\n"));
  EXPECT_THAT(ply, HasSubstr("element vertex 7\n"));
  EXPECT_THAT(ply, HasSubstr("element face 3\n"));
  EXPECT_THAT(ply, HasSubstr("property uchar red\n"));
  EXPECT_THAT(ply, HasSubstr("property list uchar int vertex_indices\n"));
  const size_t body = ply.find("end_header\n") + 11;
  ASSERT_EQ(ply.size(), body + 7 * (12 + 3) + 3 * (1 + 12));
  // The last face is mesh b's (1, 3, 2), offset by mesh a's 3 vertices.
  int32_t last[3];
  std::memcpy(last, ply.data() + ply.size() - 12, 12);
  EXPECT_EQ(last[0], 4);
  EXPECT_EQ(last[1], 6);
  EXPECT_EQ(last[2], 5);
}

TEST(PlyTest, BadTriangleAndColourCountAreNamed) {
  const auto dir = testing::ScratchDir();
  const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::array<uint32_t, 3>> bad = {{0, 1, 3}};
  const std::vector<float> rgb(9, 1.0f);
  EXPECT_THAT(WritePlyVertexColors(dir / "m.ply", positions, bad, rgb, 0).message(),
              HasSubstr("triangle 0"));
  EXPECT_THAT(
      WritePlyVertexColors(dir / "m.ply", positions, {}, std::span(rgb).first(6), 0).message(),
      HasSubstr("m.ply"));
  EXPECT_FALSE(std::filesystem::exists(dir / "m.ply"));
}

}  // namespace
}  // namespace wavebake
