#include "storage/zarr/zstd_codec.h"

#define ZSTD_STATIC_LINKING_ONLY  // ZSTD_getFrameHeader, to inspect the frame flags
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

namespace wavebake {
namespace {

using ::testing::HasSubstr;

std::vector<std::byte> SmoothFloats(size_t n) {
  std::vector<float> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = std::sin(0.001f * i);
  const auto b = std::as_bytes(std::span(v));
  return {b.begin(), b.end()};
}

std::vector<std::byte> RandomBytes(size_t n) {
  std::mt19937 rng(7);
  std::vector<std::byte> v(n);
  for (auto& b : v) b = static_cast<std::byte>(rng());
  return v;
}

TEST(ZstdCodecTest, RoundTripsAndHeaderCarriesSizeAndChecksum) {
  for (size_t n : {size_t{0}, size_t{1}, size_t{4096}, size_t{300000}}) {
    const std::vector<std::byte> src = SmoothFloats(n);
    absl::StatusOr<std::vector<std::byte>> frame = ZstdCompress(src);
    ASSERT_TRUE(frame.ok()) << frame.status();
    EXPECT_EQ(ZSTD_getFrameContentSize(frame->data(), frame->size()), src.size());
    ZSTD_frameHeader header{};
    ASSERT_EQ(ZSTD_getFrameHeader(&header, frame->data(), frame->size()), 0u);
    EXPECT_EQ(header.checksumFlag, 1u);
    EXPECT_EQ(header.frameContentSize, src.size());
    // Exactly one frame, and an independent decoder (zstd's own one-shot API) agrees.
    EXPECT_EQ(ZSTD_findFrameCompressedSize(frame->data(), frame->size()), frame->size());
    std::vector<std::byte> plain(src.size());
    EXPECT_EQ(ZSTD_decompress(plain.data(), plain.size(), frame->data(), frame->size()),
              src.size());
    EXPECT_EQ(plain, src);
    absl::StatusOr<std::vector<std::byte>> back = ZstdDecompress(*frame, src.size(), "chunk");
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_EQ(*back, src);
  }
}

TEST(ZstdCodecTest, LevelChangesTheFrameAndBadLevelIsRejected) {
  const std::vector<std::byte> src = SmoothFloats(1 << 16);
  absl::StatusOr<std::vector<std::byte>> fast = ZstdCompress(src, 1);
  absl::StatusOr<std::vector<std::byte>> strong = ZstdCompress(src, 19);
  ASSERT_TRUE(fast.ok() && strong.ok());
  EXPECT_LT(strong->size(), fast->size());
  EXPECT_EQ(ZstdCompress(src, 99).status().code(), absl::StatusCode::kInvalidArgument);
}

// A level's search with some settings replaced writes frames any decoder
// reads; settings outside zstd's bounds are refused, not clamped.
TEST(ZstdCodecTest, SearchSettingsKeepFramesReadableAndOutOfRangeOnesAreRejected) {
  const std::vector<std::byte> src = SmoothFloats(1 << 18);
  ByteBuffer frame;
  const ZstdSearch narrowed = {
      .strategy = 5, .min_match = 6, .chain_log = 16, .hash_log = 16, .search_log = 3};
  ASSERT_TRUE(ZstdCompressInto(src, 9, frame, narrowed).ok());
  std::vector<std::byte> plain(src.size());
  EXPECT_EQ(ZSTD_decompress(plain.data(), plain.size(), frame.data(), frame.size()), src.size());
  EXPECT_EQ(plain, src);
  EXPECT_FALSE(ZstdCompressInto(src, 9, frame, {.min_match = 99}).ok());
  EXPECT_FALSE(ZstdCompressInto(src, 9, frame, {.strategy = 42}).ok());
}

// Contexts are pooled and reused across levels and threads, and frame
// buffers across chunks: a chunk's frame must not depend on what was
// compressed before it (stores are byte-identical across workers and retries).
TEST(ZstdCodecTest, FramesDoNotDependOnWhatWasCompressedBefore) {
  const std::vector<std::byte> smooth = SmoothFloats(1 << 18), noise = RandomBytes(1 << 17);
  absl::StatusOr<std::vector<std::byte>> first = ZstdCompress(smooth, 9);
  ASSERT_TRUE(first.ok());
  ByteBuffer reused;
  for (int level : {-3, 9, 5, 1}) {  // other levels, searches and data through the pooled contexts
    ASSERT_TRUE(ZstdCompressInto(noise, level, reused).ok());
    ASSERT_TRUE(ZstdCompressInto(smooth, level, reused, {.min_match = 7, .hash_log = 12}).ok());
  }
  ASSERT_TRUE(ZstdCompressInto(smooth, 9, reused).ok());
  EXPECT_TRUE(std::equal(reused.begin(), reused.end(), first->begin(), first->end()));
  std::vector<std::byte> on_thread;
  std::thread([&] { on_thread = ZstdCompress(smooth, 9).value(); }).join();
  EXPECT_EQ(on_thread, *first);
}

// Random data is stored in raw blocks, so a flipped byte decodes "fine" and only
// the content checksum can catch it.
TEST(ZstdCodecTest, ChecksumCatchesCorruptionInsideRawBlock) {
  const std::vector<std::byte> src = RandomBytes(10000);
  std::vector<std::byte> frame = *ZstdCompress(src);
  frame[frame.size() / 2] ^= std::byte{0x10};
  absl::StatusOr<std::vector<std::byte>> back = ZstdDecompress(frame, src.size(), "dir/0.3");
  EXPECT_EQ(back.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(back.status().message(), HasSubstr("dir/0.3"));
  EXPECT_THAT(back.status().message(), HasSubstr("checksum"));
}

TEST(ZstdCodecTest, RejectsMalformedFrames) {
  const std::vector<std::byte> src = SmoothFloats(5000);
  const std::vector<std::byte> frame = *ZstdCompress(src);
  auto code = [&](std::span<const std::byte> f, size_t expected) {
    return ZstdDecompress(f, expected, "c").status().code();
  };
  EXPECT_EQ(code(std::span(frame).first(frame.size() - 3), src.size()),
            absl::StatusCode::kDataLoss);                               // truncated
  EXPECT_EQ(code(frame, src.size() + 4), absl::StatusCode::kDataLoss);  // wrong chunk size
  std::vector<std::byte> trailing = frame;
  trailing.push_back(std::byte{0});
  EXPECT_EQ(code(trailing, src.size()), absl::StatusCode::kDataLoss);
  EXPECT_EQ(code(RandomBytes(100), src.size()), absl::StatusCode::kDataLoss);  // not zstd
  EXPECT_EQ(code({}, 0), absl::StatusCode::kDataLoss);                         // empty file

  // A frame without a content size (numcodecs 0.11 rejects those too).
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_contentSizeFlag, 0);
  std::vector<std::byte> sizeless(ZSTD_compressBound(src.size()));
  sizeless.resize(ZSTD_compress2(cctx, sizeless.data(), sizeless.size(), src.data(), src.size()));
  ZSTD_freeCCtx(cctx);
  absl::StatusOr<std::vector<std::byte>> back = ZstdDecompress(sizeless, src.size(), "c");
  EXPECT_EQ(back.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(back.status().message(), HasSubstr("content size"));
}

TEST(ZstdCodecTest, AcceptsFramesWithoutChecksumFromOtherWriters) {
  const std::vector<std::byte> src = SmoothFloats(5000);
  std::vector<std::byte> frame(ZSTD_compressBound(src.size()));
  frame.resize(ZSTD_compress(frame.data(), frame.size(), src.data(), src.size(), 3));
  absl::StatusOr<std::vector<std::byte>> back = ZstdDecompress(frame, src.size(), "c");
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(*back, src);
}

}  // namespace
}  // namespace wavebake
