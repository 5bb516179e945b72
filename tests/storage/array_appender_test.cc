// ArrayAppender writes chunks on helper threads while the caller fills the
// next: whatever the sizes of the pieces appended, the array reads back as
// the values in order (through ZarrArray, the same bytes WriteAll writes),
// and a wrong total length is an error naming the array.
#include "storage/zarr/array_appender.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <span>

#include "storage/files/atomic_file.h"
#include "tests/storage/array_values.h"
#include "tests/storage/test_support.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;
using testing::TestValues;

ArraySpec Spec(int64_t length) {
  return {.shape = {length}, .chunks = {64}, .dtype = DTypeOf<uint32_t>(), .delta_filter = true};
}

class ArrayAppenderInFlight : public ::testing::TestWithParam<int> {};

TEST_P(ArrayAppenderInFlight, PiecesOfAnySizeReadBackInOrderAndMatchAWholeWrite) {
  TempDir tmp;
  const int64_t length = 64 * 9 + 17;  // nine full chunks and a partial one
  const std::vector<uint32_t> values = TestValues<uint32_t>(length, 7);
  absl::StatusOr<ZarrArray> appended = ZarrArray::Create(tmp.path() / "appended", Spec(length));
  absl::StatusOr<ZarrArray> whole = ZarrArray::Create(tmp.path() / "whole", Spec(length));
  ASSERT_TRUE(appended.ok() && whole.ok());
  {
    ArrayAppender<uint32_t> appender(*appended, /*in_flight=*/GetParam());
    size_t at = 0;
    for (size_t piece = 1; at < values.size(); piece = piece * 3 % 101 + 1) {
      const size_t n = std::min(piece, values.size() - at);
      ASSERT_TRUE(appender.Append(std::span(values).subspan(at, n)).ok());
      at += n;
    }
    ASSERT_TRUE(appender.Close().ok());
  }
  ASSERT_TRUE(whole->WriteAll<uint32_t>(values).ok());
  absl::StatusOr<std::vector<uint32_t>> back = appended->ReadAll<uint32_t>();
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(*back, values);
  for (int c = 0; c < 10; ++c) {  // the same chunk files, byte for byte
    const std::string name = std::to_string(c);
    EXPECT_EQ(ReadFile(tmp.path() / "appended" / name).value(),
              ReadFile(tmp.path() / "whole" / name).value())
        << "chunk " << c;
  }
}

// One chunk written at a time, and several at once: the same files.
INSTANTIATE_TEST_SUITE_P(ChunksBeingWritten, ArrayAppenderInFlight, ::testing::Values(1, 3));

// Writers of disjoint chunk ranges (FINALIZE's shards) sharing one array:
// the chunk files of a whole write, each range's length checked.
TEST(ArrayAppender, ChunkRangesWrittenApartMatchAWholeWrite) {
  TempDir tmp;
  const int64_t length = 64 * 9 + 17;
  const std::vector<uint32_t> values = TestValues<uint32_t>(length, 11);
  absl::StatusOr<ZarrArray> parts = ZarrArray::Create(tmp.path() / "parts", Spec(length));
  absl::StatusOr<ZarrArray> whole = ZarrArray::Create(tmp.path() / "whole", Spec(length));
  ASSERT_TRUE(parts.ok() && whole.ok());
  // Chunks [0, 4) and [4, 10): the second range runs to the array's end.
  for (auto [first, count] : {std::pair<int64_t, int64_t>{0, 4 * 64}, {4, -1}}) {
    ArrayAppender<uint32_t> appender(*parts, 2, first, count);
    const int64_t n = count >= 0 ? count : length - first * 64;
    ASSERT_TRUE(appender.Append(std::span(values).subspan(first * 64, n)).ok());
    ASSERT_TRUE(appender.Close().ok());
  }
  ASSERT_TRUE(whole->WriteAll<uint32_t>(values).ok());
  for (int c = 0; c < 10; ++c) {
    const std::string name = std::to_string(c);
    EXPECT_EQ(ReadFile(tmp.path() / "parts" / name).value(),
              ReadFile(tmp.path() / "whole" / name).value())
        << "chunk " << c;
  }
  ArrayAppender<uint32_t> short_range(*parts, 1, 2, 64);
  ASSERT_TRUE(short_range.Append(std::span(values).subspan(128, 10)).ok());
  EXPECT_FALSE(short_range.Close().ok());
}

TEST(ArrayAppender, AShortArrayIsAnErrorNamingIt) {
  TempDir tmp;
  absl::StatusOr<ZarrArray> array = ZarrArray::Create(tmp.path() / "short", Spec(200));
  ASSERT_TRUE(array.ok());
  ArrayAppender<uint32_t> appender(*array);
  const std::vector<uint32_t> values = TestValues<uint32_t>(150, 3);
  ASSERT_TRUE(appender.Append(values).ok());
  const absl::Status closed = appender.Close();
  EXPECT_FALSE(closed.ok());
  EXPECT_THAT(std::string(closed.message()), HasSubstr("short"));
  EXPECT_THAT(std::string(closed.message()), HasSubstr("appended 150 elements where 200 were due"));
}

// A chunk that cannot be written (its array directory is gone) fails the
// appender with the write's error, and the appender still closes and is
// destroyed without hanging on its writer threads.
TEST(ArrayAppender, AFailedChunkWriteIsReturnedAndTheWritersStop) {
  TempDir tmp;
  absl::StatusOr<ZarrArray> array = ZarrArray::Create(tmp.path() / "gone", Spec(64 * 8));
  ASSERT_TRUE(array.ok());
  std::filesystem::remove_all(tmp.path() / "gone");
  const std::vector<uint32_t> values = TestValues<uint32_t>(64 * 8, 5);
  ArrayAppender<uint32_t> appender(*array, /*in_flight=*/2);
  absl::Status status = appender.Append(values);
  if (status.ok()) status = appender.Close();
  EXPECT_FALSE(status.ok());
  EXPECT_THAT(std::string(status.message()), HasSubstr("gone"));
}

}  // namespace
}  // namespace wavebake
