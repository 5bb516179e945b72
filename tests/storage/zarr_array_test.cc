#include "storage/zarr/zarr_array.h"

#define ZSTD_STATIC_LINKING_ONLY  // ZSTD_getFrameHeader
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zstd.h>

#include <fstream>

#include "storage/files/atomic_file.h"
#include "storage/zarr/zstd_codec.h"
#include "tests/storage/array_values.h"
#include "tests/storage/test_support.h"

namespace wavebake {
namespace {

using testing::BitEqual;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using testing::PartialFiles;
using testing::TempDir;
using testing::TestValues;

struct Shape {
  std::vector<int64_t> shape, chunks;
};
// 1-D/2-D/3-D with partial edge chunks, a chunk larger than the array, and an
// empty array (nnz = 0 is a real CSC case).
const Shape kShapes[] = {
    {{300}, {128}}, {{19, 37}, {8, 16}}, {{5, 7, 3}, {4, 3, 2}}, {{10}, {64}}, {{0}, {16}},
};

template <class T>
class TypedArrayTest : public ::testing::Test {};
using ElementTypes = ::testing::Types<uint8_t, int16_t, int32_t, uint32_t, int64_t, float>;
TYPED_TEST_SUITE(TypedArrayTest, ElementTypes);

TYPED_TEST(TypedArrayTest, WholeArrayRoundTrip) {
  using T = TypeParam;
  TempDir tmp;
  int seed = 0;
  for (const Shape& s : kShapes) {
    ArraySpec spec{.shape = s.shape, .chunks = s.chunks, .dtype = DTypeOf<T>(), .fill_value = 3};
    const auto dir = tmp.path() / std::to_string(seed);
    absl::StatusOr<ZarrArray> array = ZarrArray::Create(dir, spec);
    ASSERT_TRUE(array.ok()) << array.status();
    const std::vector<T> values = TestValues<T>(ElementCount(spec), ++seed);
    ASSERT_TRUE(array->WriteAll<T>(values).ok());

    absl::StatusOr<ZarrArray> reopened = ZarrArray::Open(dir);
    ASSERT_TRUE(reopened.ok()) << reopened.status();
    EXPECT_TRUE(SameSpec(reopened->spec(), spec));
    absl::StatusOr<std::vector<T>> back = reopened->ReadAll<T>();
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_TRUE(BitEqual<T>(*back, values)) << dir;
  }
  EXPECT_THAT(PartialFiles(tmp.path()), IsEmpty());
}

TYPED_TEST(TypedArrayTest, DeltaFilterRoundTripsWrappingDifferences) {
  using T = TypeParam;
  if constexpr (std::is_integral_v<T>) {
    TempDir tmp;
    ArraySpec spec{
        .shape = {37, 50}, .chunks = {8, 16}, .dtype = DTypeOf<T>(), .delta_filter = true};
    absl::StatusOr<ZarrArray> array = ZarrArray::Create(tmp.path(), spec);
    ASSERT_TRUE(array.ok()) << array.status();
    const std::vector<T> values = TestValues<T>(ElementCount(spec), 11);
    ASSERT_TRUE(array->WriteAll<T>(values).ok());
    absl::StatusOr<std::vector<T>> back = ZarrArray::Open(tmp.path())->ReadAll<T>();
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_TRUE(BitEqual<T>(*back, values));
  }
}

// CSC indices: per column a sorted run of kept positions in a 256×256 Mallat
// layout, restarting at each column. The delta filter must pay off there.
TEST(ZarrArrayTest, DeltaFilterShrinksSortedIndices) {
  TempDir tmp;
  std::vector<uint32_t> indices;
  for (uint64_t col = 0; col < 300; ++col) {
    for (uint32_t pos = 0; pos < 65536; ++pos) {
      if (testing::Mix(col * 65536 + pos) % 200 == 0) indices.push_back(pos);
    }
  }
  auto size_with = [&](bool delta) {
    ArraySpec spec{.shape = {int64_t(indices.size())},
                   .chunks = {1 << 16},
                   .dtype = DType::kUint32,
                   .delta_filter = delta};
    const auto dir = tmp.path() / (delta ? "delta" : "plain");
    absl::StatusOr<ZarrArray> array = ZarrArray::Create(dir, spec);
    EXPECT_TRUE(array.ok() && array->WriteAll<uint32_t>(indices).ok());
    EXPECT_EQ(*ZarrArray::Open(dir)->ReadAll<uint32_t>(), indices);
    uintmax_t bytes = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) bytes += e.file_size();
    return bytes;
  };
  const uintmax_t delta = size_with(true), plain = size_with(false);
  RecordProperty("delta_bytes", std::to_string(delta));
  RecordProperty("plain_bytes", std::to_string(plain));
  EXPECT_LT(delta * 10, plain * 8) << "delta " << delta << " plain " << plain;
}

TEST(ZarrArrayTest, MissingChunksReadAsFillValue) {
  TempDir tmp;
  const ArraySpec spec{
      .shape = {20, 20}, .chunks = {8, 8}, .dtype = DType::kInt16, .fill_value = -7};
  absl::StatusOr<ZarrArray> array = ZarrArray::Create(tmp.path(), spec);
  ASSERT_TRUE(array.ok()) << array.status();
  const std::vector<int16_t> chunk = TestValues<int16_t>(64, 5);
  const std::vector<int64_t> index = {1, 1};
  ASSERT_TRUE(array->WriteChunk<int16_t>(index, chunk).ok());

  absl::StatusOr<std::vector<int16_t>> all = array->ReadAll<int16_t>();
  ASSERT_TRUE(all.ok()) << all.status();
  for (int r = 0; r < 20; ++r) {
    for (int c = 0; c < 20; ++c) {
      const bool inside = r >= 8 && r < 16 && c >= 8 && c < 16;
      const int16_t expected = inside ? chunk[(r - 8) * 8 + (c - 8)] : -7;
      ASSERT_EQ((*all)[r * 20 + c], expected) << r << "," << c;
    }
  }
  absl::StatusOr<std::vector<int16_t>> missing =
      array->ReadChunk<int16_t>(std::vector<int64_t>{2, 0});
  ASSERT_TRUE(missing.ok());
  EXPECT_EQ(*missing, std::vector<int16_t>(64, -7));
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "2.0"));
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "1.1"));
}

TEST(ZarrArrayTest, EdgeChunkKeepsItsPaddingAndFramesCarrySizeAndChecksum) {
  TempDir tmp;
  const ArraySpec spec{.shape = {10, 10}, .chunks = {4, 8}, .dtype = DType::kFloat32};
  absl::StatusOr<ZarrArray> array = ZarrArray::Create(tmp.path(), spec);
  ASSERT_TRUE(array.ok());
  const std::vector<float> chunk = TestValues<float>(32, 9);
  const std::vector<int64_t> edge = {2, 1};  // rows 8..11, cols 8..15: mostly padding
  ASSERT_TRUE(array->WriteChunk<float>(edge, chunk).ok());
  absl::StatusOr<std::vector<float>> back = array->ReadChunk<float>(edge);
  ASSERT_TRUE(back.ok());
  EXPECT_TRUE(BitEqual<float>(*back, chunk));

  absl::StatusOr<std::vector<std::byte>> file = ReadFile(tmp.path() / "2.1");
  ASSERT_TRUE(file.ok());
  EXPECT_EQ(ZSTD_getFrameContentSize(file->data(), file->size()), 32 * sizeof(float));
  ZSTD_frameHeader header{};
  ASSERT_EQ(ZSTD_getFrameHeader(&header, file->data(), file->size()), 0u);
  EXPECT_EQ(header.checksumFlag, 1u);
}

TEST(ZarrArrayTest, CorruptedChunkIsDataLossNamingTheFile) {
  TempDir tmp;
  const ArraySpec spec{.shape = {4096}, .chunks = {1024}, .dtype = DType::kUint32};
  absl::StatusOr<ZarrArray> array = ZarrArray::Create(tmp.path(), spec);
  ASSERT_TRUE(array.ok());
  ASSERT_TRUE(array->WriteAll<uint32_t>(TestValues<uint32_t>(4096, 1)).ok());
  const auto chunk_file = tmp.path() / "2";
  {
    std::fstream f(chunk_file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(std::filesystem::file_size(chunk_file) / 2));
    f.put('\x5a');
  }
  absl::StatusOr<std::vector<uint32_t>> all = array->ReadAll<uint32_t>();
  EXPECT_EQ(all.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(all.status().message(), HasSubstr(chunk_file.string()));

  std::filesystem::resize_file(tmp.path() / "1", 10);
  absl::StatusOr<std::vector<std::byte>> truncated = array->ReadChunk(std::vector<int64_t>{1});
  EXPECT_EQ(truncated.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(truncated.status().message(), HasSubstr((tmp.path() / "1").string()));
}

TEST(ZarrArrayTest, SameArrayWrittenTwiceIsBitIdentical) {
  TempDir tmp;
  const ArraySpec spec{
      .shape = {33, 17}, .chunks = {8, 8}, .dtype = DType::kInt64, .fill_value = -1};
  const std::vector<int64_t> values = TestValues<int64_t>(33 * 17, 4);
  for (const char* name : {"a", "b"}) {
    ASSERT_TRUE(ZarrArray::Create(tmp.path() / name, spec)->WriteAll<int64_t>(values).ok());
  }
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(tmp.path() / "a")) {
    const auto other = tmp.path() / "b" / entry.path().filename();
    EXPECT_EQ(*ReadFile(entry.path()), *ReadFile(other)) << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 1 + 5 * 3);  // .zarray and every chunk
}

TEST(ZarrArrayTest, CreateIsIdempotentButRefusesADifferentSpec) {
  TempDir tmp;
  ArraySpec spec{.shape = {100},
                 .chunks = {10},
                 .dtype = DType::kFloat32,
                 .fill_value = std::numeric_limits<double>::quiet_NaN()};
  absl::StatusOr<ZarrArray> first = ZarrArray::Create(tmp.path(), spec);
  ASSERT_TRUE(first.ok()) << first.status();
  ASSERT_TRUE(first->WriteChunk<float>(std::vector<int64_t>{3}, std::vector<float>(10, 2.5f)).ok());
  absl::StatusOr<ZarrArray> again = ZarrArray::Create(tmp.path(), spec);  // a retried task
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ((*again->ReadChunk<float>(std::vector<int64_t>{3}))[0], 2.5f);  // chunk kept
  EXPECT_TRUE(std::isnan((*again->ReadChunk<float>(std::vector<int64_t>{4}))[0]));

  spec.chunks = {20};
  absl::StatusOr<ZarrArray> other = ZarrArray::Create(tmp.path(), spec);
  EXPECT_EQ(other.status().code(), absl::StatusCode::kAlreadyExists);
  EXPECT_THAT(other.status().message(), HasSubstr(".zarray"));
}

// A chunk copied as encoded: the source file's bytes, whatever encoding they
// hold (here level 19, not the spec's), reading back as the source's values.
TEST(ZarrArrayTest, CopyChunkFromKeepsTheEncodedBytes) {
  TempDir tmp;
  const ArraySpec spec{.shape = {40}, .chunks = {10}, .dtype = DType::kFloat32};
  absl::StatusOr<ZarrArray> from = ZarrArray::Create(tmp.path() / "from", spec);
  absl::StatusOr<ZarrArray> to = ZarrArray::Create(tmp.path() / "to", spec);
  ASSERT_TRUE(from.ok() && to.ok());
  const std::vector<float> values = TestValues<float>(10, 7);
  absl::StatusOr<std::vector<std::byte>> frame = ZstdCompress(std::as_bytes(std::span(values)), 19);
  ASSERT_TRUE(frame.ok());
  const std::vector<int64_t> index{2};
  ASSERT_TRUE(AtomicWriteFile(from->ChunkPath(index), *frame).ok());

  ASSERT_TRUE(to->CopyChunkFrom(*from, index).ok());
  EXPECT_EQ(*ReadFile(to->ChunkPath(index)), *frame);
  EXPECT_TRUE(BitEqual<float>(*to->ReadChunk<float>(index), values));

  const std::vector<int64_t> never_written{1};
  EXPECT_EQ(to->CopyChunkFrom(*from, never_written).code(), absl::StatusCode::kNotFound);
  EXPECT_FALSE(std::filesystem::exists(to->ChunkPath(never_written)));
  ArraySpec other_spec = spec;
  other_spec.zstd_level = 5;
  absl::StatusOr<ZarrArray> other = ZarrArray::Create(tmp.path() / "other", other_spec);
  ASSERT_TRUE(other.ok());
  const absl::Status refused = other->CopyChunkFrom(*from, index);
  EXPECT_EQ(refused.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(refused.message(), HasSubstr("different specs"));
}

}  // namespace
}  // namespace wavebake
