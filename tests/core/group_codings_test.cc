// ChooseGroupCodings (core/columns/group_codings.h) with byte counters whose
// answer is known: the group keeps the choice they rank smaller, and the
// fewest-coefficient codings on a tie.
#include "core/columns/group_codings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace wavebake {
namespace {

constexpr int kGroupW = 16, kGroupH = 16;

// Smooth columns with sparse spikes: some code deep, some at depth 0.
std::vector<ColumnCodings> MixedGroup(const ColumnCodingParams& p, int columns) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<ColumnCodings> group(columns);
  for (ColumnCodings& c : group) {
    const float smooth = u(rng), spikes = u(rng);
    std::vector<float> v(kGroupW * kGroupH);
    for (int i = 0; i < kGroupW * kGroupH; ++i)
      v[i] = smooth * (1 + std::sin(0.2f * (i % kGroupW) + 0.3f * (i / kGroupW))) +
             (u(rng) < 0.15f ? spikes * 3 * u(rng) : 0.0f);
    CodeColumn(p, v, &c.fewest, 0.0, &c.flat);
  }
  return group;
}

ColumnCodingParams GroupParams() {
  return {.width = kGroupW, .height = kGroupH, .target_error = 0.05, .matrix_energy = 100.0};
}

size_t CountBytes(std::span<const uint32_t> positions, std::span<const int16_t>) {
  return positions.size();
}
size_t InverseCountBytes(std::span<const uint32_t> positions, std::span<const int16_t>) {
  return (size_t{1} << 40) - positions.size();
}
size_t ConstantBytes(std::span<const uint32_t>, std::span<const int16_t>) { return 7; }

TEST(GroupCodingsTest, FewestCoefficientsWinWhenBytesFollowTheCount) {
  const std::vector<ColumnCodings> group = MixedGroup(GroupParams(), 40);
  int with_flat = 0;
  for (const ColumnCodings& c : group) with_flat += c.flat.depth == 0;
  ASSERT_GT(with_flat, 5);  // the group does have a choice
  EXPECT_EQ(ChooseGroupCodings(GroupParams(), group, 0, CountBytes), std::vector<uint8_t>(40, 0));
  EXPECT_EQ(ChooseGroupCodings(GroupParams(), group, 0, ConstantBytes),
            std::vector<uint8_t>(40, 0));  // tie
}

// With bytes that grow as coefficients go, the group keeps its columns'
// depth-0 codings where their estimate says so: only columns that have one,
// and some of them.
TEST(GroupCodingsTest, DepthZeroCodingsAreKeptWhenTheBytesSaySo) {
  const std::vector<ColumnCodings> group = MixedGroup(GroupParams(), 40);
  const std::vector<uint8_t> kept = ChooseGroupCodings(GroupParams(), group, 0, InverseCountBytes);
  int flat = 0;
  for (size_t c = 0; c < group.size(); ++c) {
    if (kept[c]) {
      EXPECT_EQ(group[c].flat.depth, 0) << "column " << c;
    }
    flat += kept[c];
  }
  EXPECT_GT(flat, 0);
}

TEST(GroupCodingsTest, AGroupWithoutAlternativesIsNotMeasured) {
  std::vector<ColumnCodings> group(3);  // empty columns: no depth-0 alternative
  for (ColumnCodings& c : group) c.flat.depth = -1;
  EXPECT_EQ(ChooseGroupCodings(GroupParams(), group, 0,
                               [](std::span<const uint32_t>, std::span<const int16_t>) -> size_t {
                                 ADD_FAILURE() << "bytes counted";
                                 return 0;
                               }),
            std::vector<uint8_t>(3, 0));
}

TEST(GroupCodingsTest, OnlyAdaptiveWithATargetAndUniformScalingCompares) {
  ColumnCodingParams p = GroupParams();
  EXPECT_TRUE(ComparesCodedSize(p));
  p.column_terms = 8;
  EXPECT_FALSE(ComparesCodedSize(p));
  p = GroupParams();
  p.level_scaling = LevelScaling::kPaper;
  EXPECT_FALSE(ComparesCodedSize(p));
  p = GroupParams();
  p.mode = ColumnMode::k2d;
  EXPECT_FALSE(ComparesCodedSize(p));
}

}  // namespace
}  // namespace wavebake
