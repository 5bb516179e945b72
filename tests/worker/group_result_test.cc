// The group result file (worker/columns/group_result.h): what TRANSFORM_COLUMNS
// writes reads back field for field, the column table reads back alone, and
// every kind of damage is DataLoss naming the file — never a crash, a huge
// allocation or a silently wrong group.
#include "worker/columns/group_result.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/testing/scratch_dir.h"

namespace wavebake {
namespace {

using test_support::ScratchDir;
using ::testing::HasSubstr;

GroupColumn TestColumn(uint8_t depth, uint32_t kept, double energy) {
  return {.depth = depth,
          .min_bits = uint8_t(3 + depth),
          .kept = kept,
          .energy = energy,
          .reference_energy = 2 * energy,
          .dropped_energy = energy / 7,
          .max_abs = energy / 3,
          .step_unit = energy / 11};
}

// Three columns, the middle one keeping nothing.
GroupResult SampleGroup(int group) {
  GroupResult r;
  r.group = group;
  r.first_column = 100 * group;
  r.matrix_energy = 0.125;
  r.columns = {TestColumn(2, 3, 1.5), TestColumn(0, 0, 0.0), TestColumn(5, 2, 0.25)};
  r.positions = {1, 7, 4095, 0, 9};
  r.values = {0.5f, -1e-7f, 3.25f, -2.0f, 1e30f};
  return r;
}

void ExpectSameColumns(const GroupResult& got, const GroupResult& want) {
  EXPECT_EQ(got.group, want.group);
  EXPECT_EQ(got.first_column, want.first_column);
  EXPECT_EQ(got.matrix_energy, want.matrix_energy);
  ASSERT_EQ(got.columns.size(), want.columns.size());
  for (size_t c = 0; c < want.columns.size(); ++c) {
    const GroupColumn &g = got.columns[c], &w = want.columns[c];
    EXPECT_EQ(g.depth, w.depth) << c;
    EXPECT_EQ(g.min_bits, w.min_bits) << c;
    EXPECT_EQ(g.kept, w.kept) << c;
    EXPECT_EQ(g.energy, w.energy) << c;
    EXPECT_EQ(g.reference_energy, w.reference_energy) << c;
    EXPECT_EQ(g.dropped_energy, w.dropped_energy) << c;
    EXPECT_EQ(g.max_abs, w.max_abs) << c;
    EXPECT_EQ(g.step_unit, w.step_unit) << c;
  }
}

std::vector<char> GroupFileBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void WriteGroupFile(const std::filesystem::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
}

// Writes group 1's file under `dir`, then lets `damage` change its bytes.
template <class Damage>
std::filesystem::path WriteDamagedGroup(const std::filesystem::path& dir, Damage damage) {
  EXPECT_TRUE(WriteGroupResult(dir, SampleGroup(1)).ok());
  const auto path = GroupResultPath(dir, 1);
  std::vector<char> bytes = GroupFileBytes(path);
  damage(bytes);
  WriteGroupFile(path, bytes);
  return path;
}

// Both reads of `group` are DataLoss with `why` in the message.
void ExpectBothReadsLost(const std::filesystem::path& dir, int group, const std::string& why) {
  for (const absl::Status& s :
       {ReadGroupResult(dir, group).status(), ReadGroupColumns(dir, group).status()}) {
    EXPECT_TRUE(absl::IsDataLoss(s)) << s;
    EXPECT_THAT(s.message(), HasSubstr(why));
  }
}

TEST(GroupResultTest, ReadsBackWhatWasWritten) {
  ScratchDir dir;
  const GroupResult want = SampleGroup(3);
  ASSERT_TRUE(WriteGroupResult(dir.path(), want).ok());
  absl::StatusOr<GroupResult> got = ReadGroupResult(dir.path(), 3);
  ASSERT_TRUE(got.ok()) << got.status();
  ExpectSameColumns(*got, want);
  EXPECT_THAT(got->positions, ::testing::ElementsAreArray(want.positions));
  EXPECT_THAT(got->values, ::testing::ElementsAreArray(want.values));
}

TEST(GroupResultTest, ColumnTableReadsAlone) {
  ScratchDir dir;
  const GroupResult want = SampleGroup(4);
  ASSERT_TRUE(WriteGroupResult(dir.path(), want).ok());
  absl::StatusOr<GroupResult> got = ReadGroupColumns(dir.path(), 4);
  ASSERT_TRUE(got.ok()) << got.status();
  ExpectSameColumns(*got, want);
  EXPECT_TRUE(got->positions.empty());
  EXPECT_TRUE(got->values.empty());
}

TEST(GroupResultTest, GroupThatKeptNothing) {
  ScratchDir dir;
  GroupResult want = SampleGroup(0);
  for (GroupColumn& c : want.columns) c.kept = 0;
  want.positions.clear();
  want.values.clear();
  ASSERT_TRUE(WriteGroupResult(dir.path(), want).ok());
  absl::StatusOr<GroupResult> got = ReadGroupResult(dir.path(), 0);
  ASSERT_TRUE(got.ok()) << got.status();
  ExpectSameColumns(*got, want);
  EXPECT_TRUE(got->positions.empty());
}

TEST(GroupResultTest, MissingIsNotFound) {
  ScratchDir dir;
  EXPECT_TRUE(absl::IsNotFound(ReadGroupResult(dir.path(), 2).status()));
  EXPECT_TRUE(absl::IsNotFound(ReadGroupColumns(dir.path(), 2).status()));
}

// Every cut of the file, from empty to one byte short, fails the full read;
// the table-only read fails as long as the cut reaches into the table.
TEST(GroupResultTest, TruncatedFileIsDataLoss) {
  ScratchDir dir;
  ASSERT_TRUE(WriteGroupResult(dir.path(), SampleGroup(1)).ok());
  const auto path = GroupResultPath(dir.path(), 1);
  const std::vector<char> whole = GroupFileBytes(path);
  ASSERT_TRUE(ReadGroupColumns(dir.path(), 1).ok());
  size_t table_end = 0;  // the shortest cut the table-only read accepts
  for (size_t cut = 0; cut < whole.size(); ++cut) {
    WriteGroupFile(path, std::vector<char>(whole.begin(), whole.begin() + cut));
    const absl::Status full = ReadGroupResult(dir.path(), 1).status();
    EXPECT_TRUE(absl::IsDataLoss(full)) << "cut " << cut << ": " << full;
    EXPECT_THAT(full.message(), HasSubstr(path.string())) << "cut " << cut;
    const absl::Status table = ReadGroupColumns(dir.path(), 1).status();
    if (table.ok() && table_end == 0) table_end = cut;  // from here on, every cut holds it
    if (table_end == 0) {
      EXPECT_TRUE(absl::IsDataLoss(table)) << "cut " << cut << ": " << table;
    } else {
      EXPECT_TRUE(table.ok()) << "cut " << cut << ": " << table;
    }
  }
  // The table is a small frame after a 32-byte preamble, well before the end.
  EXPECT_GT(table_end, 32u);
  EXPECT_LT(table_end, whole.size());
}

// A damaged byte in the values is caught by its frame's checksum; the table
// alone does not read that frame.
TEST(GroupResultTest, DamagedValuesAreDataLoss) {
  ScratchDir dir;
  const auto path = WriteDamagedGroup(dir.path(), [](std::vector<char>& bytes) {
    bytes[bytes.size() - 8] ^= 0x40;  // inside the last frame, before its checksum
  });
  const absl::Status s = ReadGroupResult(dir.path(), 1).status();
  EXPECT_TRUE(absl::IsDataLoss(s)) << s;
  EXPECT_THAT(s.message(), HasSubstr(path.string()));
  EXPECT_TRUE(ReadGroupColumns(dir.path(), 1).ok());
}

TEST(GroupResultTest, BadMagicIsDataLoss) {
  ScratchDir dir;
  WriteDamagedGroup(dir.path(), [](std::vector<char>& bytes) {
    bytes[7] = '2';  // the format before the column table stood alone
  });
  ExpectBothReadsLost(dir.path(), 1, "bad magic");
}

// A frame size far beyond any real group is refused before anything is
// allocated or read for it.
TEST(GroupResultTest, AbsurdFrameSizeIsDataLoss) {
  ScratchDir dir;
  WriteDamagedGroup(dir.path(), [](std::vector<char>& bytes) {
    const uint64_t huge = uint64_t{1} << 62;
    std::memcpy(bytes.data() + 8, &huge, sizeof huge);  // the table frame's size
  });
  ExpectBothReadsLost(dir.path(), 1, "frame size");
}

// Another group's file under this group's name is not taken for it.
TEST(GroupResultTest, WrongGroupIsDataLoss) {
  ScratchDir dir;
  ASSERT_TRUE(WriteGroupResult(dir.path(), SampleGroup(1)).ok());
  std::filesystem::copy_file(GroupResultPath(dir.path(), 1), GroupResultPath(dir.path(), 2));
  ExpectBothReadsLost(dir.path(), 2, "holds group 1");
}

}  // namespace
}  // namespace wavebake
