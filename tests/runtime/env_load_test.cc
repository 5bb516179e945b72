// LoadEnvMap: formats, layouts and errors that name the file and pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "env_test_util.h"
#include "gmock/gmock.h"
#include "runtime/io/image_io.h"
#include "runtime/io/stb_codecs.h"
#include "runtime/relight/lighting.h"
#include "storage/files/atomic_file.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

absl::Status LoadExr(const EnvMap& image, const std::string& name) {
  const auto path = testing::ScratchDir() / name;
  if (absl::Status s = WriteExr(path, image.width, image.height, image.rgb); !s.ok()) return s;
  absl::StatusOr<EnvMap> env = LoadEnvMap(path.string());
  return env.status();
}

TEST(LoadEnvTest, ProbesAreLatLong) {
  const absl::StatusOr<EnvMap> env = LoadEnvMap(testing::ProbePath("grace.hdr"));
  ASSERT_TRUE(env.ok()) << env.status();
  EXPECT_EQ(env->width, 256);
  EXPECT_EQ(env->height, 128);
  EXPECT_EQ(env->rgb.size(), 256u * 128 * 3);
}

TEST(LoadEnvTest, RadianceHdrRoundTripsWithinRgbePrecision) {
  EnvMap image = testing::UniformEnv(16, 8, 0.25f);
  testing::SetPixel(image, 3, 2, {100, 7, 0.5f});
  const auto path = testing::ScratchDir() / "small.hdr";
  absl::StatusOr<std::vector<std::byte>> hdr =
      EncodeRadianceHdr(image.width, image.height, image.rgb);
  ASSERT_TRUE(hdr.ok()) << hdr.status();
  ASSERT_TRUE(AtomicWriteFile(path, *hdr).ok());
  const absl::StatusOr<EnvMap> env = LoadEnvMap(path.string());
  ASSERT_TRUE(env.ok()) << env.status();
  ASSERT_EQ(env->rgb.size(), image.rgb.size());
  // RGBE keeps 8 mantissa bits relative to the largest channel.
  for (size_t i = 0; i < image.rgb.size(); ++i) {
    const float max_channel = i / 3 == 2 * 16 + 3 ? 100.0f : 0.25f;
    EXPECT_NEAR(env->rgb[i], image.rgb[i], max_channel / 64) << i;
  }
}

TEST(LoadEnvTest, MissingFileIsNamed) {
  const absl::StatusOr<EnvMap> env = LoadEnvMap("/nonexistent/dir/probe.hdr");
  EXPECT_EQ(env.status().code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(env.status().message(), HasSubstr("/nonexistent/dir/probe.hdr"));
}

TEST(LoadEnvTest, CorruptHdrIsNamed) {
  const auto path = testing::ScratchDir() / "corrupt.hdr";
  std::ofstream(path) << "#?RADIANCE\nnot really\n";
  const absl::StatusOr<EnvMap> env = LoadEnvMap(path.string());
  EXPECT_EQ(env.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(env.status().message(), HasSubstr(path.string()));
}

TEST(LoadEnvTest, CorruptExrIsNamed) {
  const auto path = testing::ScratchDir() / "corrupt.exr";
  std::ofstream(path) << "v/1\x01 garbage";
  const absl::StatusOr<EnvMap> env = LoadEnvMap(path.string());
  EXPECT_FALSE(env.ok());
  EXPECT_THAT(env.status().message(), HasSubstr(path.string()));
}

TEST(LoadEnvTest, UnknownFormatAndBuiltinAreRejected) {
  const auto path = testing::ScratchDir() / "probe.png";
  std::ofstream(path) << "x";
  EXPECT_THAT(LoadEnvMap(path.string()).status().message(), HasSubstr("probe.png"));
  EXPECT_THAT(LoadEnvMap("builtin:moon").status().message(), HasSubstr("builtin:moon"));
}

TEST(LoadEnvTest, WrongAspectRatioIsNamed) {
  const absl::Status s = LoadExr(testing::UniformEnv(30, 20, 1), "square-ish.exr");
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("square-ish.exr"));
  EXPECT_THAT(s.message(), HasSubstr("30x20"));
}

struct BadTexel {
  const char* name;
  float value;
};

class BadTexelTest : public ::testing::TestWithParam<BadTexel> {};

TEST_P(BadTexelTest, NamesFileAndFirstPixel) {
  EnvMap image = testing::UniformEnv(32, 16, 1);
  testing::SetPixel(image, 21, 5, {1, GetParam().value, 1});
  testing::SetPixel(image, 2, 9, {GetParam().value, 1, 1});  // a later row: not the first
  const absl::Status s = LoadExr(image, std::string(GetParam().name) + ".exr");
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr(std::string(GetParam().name) + ".exr"));
  EXPECT_THAT(s.message(), HasSubstr("pixel (21, 5) channel G"));
}

INSTANTIATE_TEST_SUITE_P(Values, BadTexelTest,
                         ::testing::Values(BadTexel{"nan", std::numeric_limits<float>::quiet_NaN()},
                                           BadTexel{"inf", std::numeric_limits<float>::infinity()},
                                           BadTexel{"negative", -0.5f},
                                           BadTexel{"overflowing", 3e38f},
                                           BadTexel{"past_the_limit", 2 * kMaxEnvRadiance}),
                         [](const auto& info) { return std::string(info.param.name); });

// An RGBE exponent of 255 decodes to 1.7e38: finite, but a block of it
// overflowed the float lighting transform and relit silently black.
TEST(LoadEnvTest, RgbeExponent255IsRefusedNamingTheTexel) {
  // The flat texels of a hand-made file: (128, 128, 128, 129) is 1.0.
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32 +X 64\n";
  std::string text = header;
  for (int i = 0; i < 64 * 32; ++i)
    text += (i == 5 * 64 + 9) ? "\xff\xff\xff\xff" : "\x80\x80\x80\x81";
  const auto path = testing::ScratchDir() / "e255.hdr";
  std::ofstream(path, std::ios::binary) << text;
  const absl::Status s = LoadEnvMap(path.string()).status();
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("e255.hdr: pixel (9, 5) channel R"));
  EXPECT_THAT(s.message(), HasSubstr("overflows"));
}

// At the limit everywhere (the most energy a map may carry) the lighting of
// the finest cubemap tried here is finite, well inside the bound of
// env_map.h (every coefficient ≤ √(6N²)·max L).
TEST(LoadEnvTest, TheBrightestAllowedMapProjectsToFiniteLighting) {
  const EnvMap image = testing::UniformEnv(64, 32, kMaxEnvRadiance);
  const auto path = testing::ScratchDir() / "max.exr";
  ASSERT_TRUE(WriteExr(path, image.width, image.height, image.rgb).ok());
  const absl::StatusOr<EnvMap> env = LoadEnvMap(path.string());
  ASSERT_TRUE(env.ok()) << env.status();
  const int n = 128;
  for (WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kDaub4}) {
    absl::StatusOr<LightingCoefficients> l = LightingFromEnv(*env, n, f);
    ASSERT_TRUE(l.ok()) << l.status();
    for (float c : l->rgb) {
      ASSERT_TRUE(std::isfinite(c));
      ASSERT_LE(std::fabs(c), std::sqrt(6.0 * n * n) * kMaxEnvRadiance * 1.001);
    }
  }
}

}  // namespace
}  // namespace wavebake
