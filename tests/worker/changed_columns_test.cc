// The changed-column record of an in-place update's tile
// (worker/tiles/changed_columns.h): a column is changed where any old row
// differs from the new one in any bit (so -0 against 0 counts, as a memcmp
// of the chunks sees it, and cells not listed are not looked at); the
// record reads back bit for bit at any column offset, a short record is
// DataLoss naming the file, a missing one NotFound.
#include "worker/tiles/changed_columns.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <vector>

#include "storage/store/store_layout.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake {
namespace {

using test_support::ScratchDir;
using ::testing::HasSubstr;

TEST(ChangedColumnsTest, AnyBitOfAListedCellChangesItsColumn) {
  constexpr int kColumns = 5;
  constexpr size_t kStride = 8;  // padded rows, as BAKE_TILE lays them out
  std::vector<float> rows(3 * kStride, 1.0f);
  OldRows old{.cells = {0, 2}, .values = std::vector<float>(2 * kColumns, 1.0f)};
  rows[0 * kStride + 1] = -0.0f;  // cell 0, column 1: was +0
  old.values[0 * kColumns + 1] = 0.0f;
  rows[2 * kStride + 3] = 1.0000001f;   // cell 2, column 3: one ulp up
  rows[1 * kStride + 4] = 7.0f;         // cell 1 is not listed (an old row, copied)
  rows[2 * kStride + kColumns] = 9.0f;  // padding past the row
  std::vector<uint8_t> changed(kColumns, 0);
  OrChangedColumns(old, rows, kStride, changed);
  EXPECT_EQ(changed, (std::vector<uint8_t>{0, 1, 0, 1, 0}));
  changed[0] = 1;  // ORs: what is set stays set
  OrChangedColumns(old, rows, kStride, changed);
  EXPECT_EQ(changed, (std::vector<uint8_t>{1, 1, 0, 1, 0}));
}

TEST(ChangedColumnsTest, TheRecordReadsBackAtAnyOffset) {
  ScratchDir dir;
  constexpr int kColumns = 37;  // not a multiple of 8
  std::mt19937 rng(3);
  std::vector<uint8_t> a(kColumns), b(kColumns);
  for (int m = 0; m < kColumns; ++m) a[m] = rng() % 3 == 0, b[m] = rng() % 5 == 0;
  ASSERT_TRUE(WriteChangedColumns(dir.path(), 4, a).ok());
  ASSERT_TRUE(WriteChangedColumns(dir.path(), 9, b).ok());
  for (int first : {0, 5, 16, 30}) {
    std::vector<uint8_t> got(kColumns - first, 0);
    ASSERT_TRUE(OrChangedColumns(dir.path(), 4, first, got).ok());
    ASSERT_TRUE(OrChangedColumns(dir.path(), 9, first, got).ok());
    for (int j = 0; j < kColumns - first; ++j)
      EXPECT_EQ(got[j], a[first + j] | b[first + j]) << "first " << first << " j " << j;
  }
  std::vector<uint8_t> past(kColumns + 8, 0);  // asks for columns the record does not hold
  const absl::Status short_record = OrChangedColumns(dir.path(), 4, 0, past);
  EXPECT_EQ(short_record.code(), absl::StatusCode::kDataLoss) << short_record;
  EXPECT_THAT(short_record.message(), HasSubstr(store::kStagingChanged));
  EXPECT_EQ(OrChangedColumns(dir.path(), 5, 0, past).code(), absl::StatusCode::kNotFound);
  RemoveChangedColumns(dir.path());
  EXPECT_FALSE(std::filesystem::exists(store::Path(dir.path(), store::kStagingChanged)));
}

}  // namespace
}  // namespace wavebake
