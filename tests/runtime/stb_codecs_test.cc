// The private stb_image (runtime/io/stb_codecs.h): round trips, and every
// truncation of a Radiance or PNG file is an error naming the file — the
// copy the program used to reach (libdraco's) looped forever on them. The
// time limit of these hangs is in tests/scripts/corrupt_inputs.sh.
#include "runtime/io/stb_codecs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "env_test_util.h"
#include "storage/files/atomic_file.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

std::vector<std::byte> Hdr(int w, int h) {
  std::vector<float> rgb(size_t(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.1f + float(i % 17) * std::exp2(float(i % 5));
  absl::StatusOr<std::vector<std::byte>> hdr = EncodeRadianceHdr(w, h, rgb);
  EXPECT_TRUE(hdr.ok()) << hdr.status();
  return hdr.ok() ? *hdr : std::vector<std::byte>{};
}

std::span<const std::byte> Prefix(const std::vector<std::byte>& b, size_t n) {
  return std::span(b).first(n);
}

// Widths 4 and 40000 are stored flat, 16 and 300 run-length encoded; the
// smallest files are shorter than stb's read-ahead, which is no truncation.
TEST(StbCodecsTest, RadianceRoundTripsWithinRgbePrecisionAtEveryEncoding) {
  for (auto [w, h] : {std::pair{1, 1}, {4, 2}, {16, 8}, {300, 3}, {40000, 1}}) {
    std::vector<float> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.5f + float(i % 7);
    absl::StatusOr<std::vector<std::byte>> hdr = EncodeRadianceHdr(w, h, rgb);
    ASSERT_TRUE(hdr.ok()) << hdr.status();
    absl::StatusOr<EnvMap> back = DecodeRadianceHdr(*hdr, "x.hdr");
    ASSERT_TRUE(back.ok()) << w << "x" << h << ": " << back.status();
    ASSERT_EQ(back->width, w);
    ASSERT_EQ(back->height, h);
    for (size_t i = 0; i < rgb.size(); ++i) ASSERT_NEAR(back->rgb[i], rgb[i], 7.0 / 128) << i;
  }
}

TEST(StbCodecsTest, EveryTruncatedRadianceFileIsAnErrorNamingIt) {
  for (auto [w, h] : {std::pair{4, 3}, {16, 8}, {300, 2}}) {
    const std::vector<std::byte> hdr = Hdr(w, h);
    for (size_t n = 0; n < hdr.size(); ++n) {
      absl::StatusOr<EnvMap> env = DecodeRadianceHdr(Prefix(hdr, n), "cut.hdr");
      ASSERT_FALSE(env.ok()) << w << "x" << h << " cut at " << n << " of " << hdr.size();
      EXPECT_EQ(env.status().code(), absl::StatusCode::kInvalidArgument);
      EXPECT_THAT(env.status().message(), HasSubstr("cut.hdr"));
    }
  }
}

// The probe the hang was found with, cut at many places (50000 among them).
TEST(StbCodecsTest, TruncatedProbeIsAnError) {
  absl::StatusOr<std::vector<std::byte>> grace = ReadFile(testing::ProbePath("grace.hdr"));
  ASSERT_TRUE(grace.ok()) << grace.status();
  ASSERT_TRUE(DecodeRadianceHdr(*grace, "grace.hdr").ok());
  for (size_t n : {size_t{50000}, size_t{0}, size_t{11}, size_t{118}, size_t{119}, size_t{120}}) {
    absl::StatusOr<EnvMap> env = DecodeRadianceHdr(Prefix(*grace, n), "t.hdr");
    EXPECT_THAT(env.status().message(), HasSubstr("t.hdr")) << n;
  }
  for (size_t n = 1000; n < grace->size(); n += 997) {
    absl::StatusOr<EnvMap> env = DecodeRadianceHdr(Prefix(*grace, n), "t.hdr");
    ASSERT_FALSE(env.ok()) << n;
    EXPECT_THAT(env.status().message(), HasSubstr("truncated")) << n << ": " << env.status();
  }
}

// Zero run counts in the middle (not at the end) are odd data, not a loop.
TEST(StbCodecsTest, CorruptRunCountsEnd) {
  std::vector<std::byte> hdr = Hdr(16, 8);
  for (size_t i = hdr.size() / 2; i < hdr.size(); i += 3) hdr[i] = std::byte{0};
  const absl::StatusOr<EnvMap> env = DecodeRadianceHdr(hdr, "zeros.hdr");
  if (!env.ok()) {
    EXPECT_THAT(env.status().message(), HasSubstr("zeros.hdr"));
  }
}

TEST(StbCodecsTest, AHeaderThatPromisesMoreThanTheFileHoldsIsRefusedBeforeDecoding) {
  const std::string text = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16000 +X 16000\n\x02\x02";
  const std::span<const std::byte> bytes = std::as_bytes(std::span(text));
  const absl::StatusOr<EnvMap> env = DecodeRadianceHdr(bytes, "huge.hdr");
  EXPECT_THAT(env.status().message(), HasSubstr("huge.hdr: truncated Radiance HDR: 16000x16000"));
  const std::string png_named = "\x89PNG\r\n\x1a\n";
  EXPECT_THAT(DecodeRadianceHdr(std::as_bytes(std::span(png_named)), "p.hdr").status().message(),
              HasSubstr("not a Radiance HDR"));
}

TEST(StbCodecsTest, PngRoundTripsAndEveryTruncationIsAnError) {
  const int w = 13, h = 7;
  std::vector<uint8_t> rgb(w * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>(i * 37);
  absl::StatusOr<std::vector<std::byte>> png = EncodePng(w, h, 3, rgb);
  ASSERT_TRUE(png.ok()) << png.status();
  absl::StatusOr<Rgb8Image> back = DecodePng(*png, "a.png");
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->width, w);
  EXPECT_EQ(back->rgb, rgb);
  for (size_t n = 0; n < png->size(); ++n) {
    absl::StatusOr<Rgb8Image> cut = DecodePng(Prefix(*png, n), "cut.png");
    ASSERT_FALSE(cut.ok()) << n << " of " << png->size();
    EXPECT_THAT(cut.status().message(), HasSubstr("cut.png"));
  }
}

// A header claiming more pixels than any file this size can hold is refused
// before stb allocates them (the fuzzer's PNGs made it allocate 2 GB).
TEST(StbCodecsTest, APngHeaderPromisingMoreThanItsSizeIsRefused) {
  absl::StatusOr<std::vector<std::byte>> png = EncodePng(2, 2, 3, std::vector<uint8_t>(12, 7));
  ASSERT_TRUE(png.ok());
  std::vector<std::byte> big = *png;
  // IHDR's width and height (big-endian at 16 and 20) → 8000 × 8000.
  for (int at : {16, 20}) {
    big[at] = std::byte{0}, big[at + 1] = std::byte{0}, big[at + 2] = std::byte{0x1f},
    big[at + 3] = std::byte{0x40};
  }
  const absl::StatusOr<Rgb8Image> image = DecodePng(big, "big.png");
  EXPECT_THAT(image.status().message(), HasSubstr("big.png: PNG of 8000x8000 pixels"));
}

// A chunk declaring more bytes than the file has left is refused before stb
// grows its buffer to the declared length (a 168-byte file made it fill 2 GB).
TEST(StbCodecsTest, AChunkLongerThanTheFileIsRefusedByName) {
  absl::StatusOr<std::vector<std::byte>> png = EncodePng(2, 2, 3, std::vector<uint8_t>(12, 7));
  ASSERT_TRUE(png.ok());
  std::vector<std::byte> bad = *png;
  const size_t idat = 8 + 12 + 13;  // signature, then IHDR with its 13 bytes
  ASSERT_EQ(std::string(reinterpret_cast<const char*>(bad.data()) + idat + 4, 4), "IDAT");
  bad[idat] = std::byte{0x7c};  // its length → ~2 GB
  EXPECT_THAT(DecodePng(bad, "long.png").status().message(),
              HasSubstr("long.png: truncated PNG: chunk 'IDAT' at byte 33 declares"));
  EXPECT_THAT(DecodePng(std::vector<std::byte>(20, std::byte{'x'}), "text.png").status().message(),
              HasSubstr("text.png: not a PNG file"));
}

}  // namespace
}  // namespace wavebake
