// CodeColumn on columns whose whole energy fits their share of the error
// budget (DESIGN.md §1 "Coefficient selection": dropped energy ≤
// target²·E_ref): keeping nothing meets the budget at depth 0, and no depth
// can keep fewer than nothing, so the adaptive rule (fewest kept, ties: the
// shallower) picks depth 0. The reference is the definition itself, counted
// at every depth with core/columns/nla.h.
#include "core/columns/column_coding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/columns/nla.h"
#include "core/columns/uncovered_fill.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

constexpr int kW = 16, kH = 8;

std::vector<float> RandomColumn(std::mt19937& rng) {
  std::normal_distribution<float> normal(0, 1);
  std::vector<float> v(kW * kH);
  for (float& x : v) x = normal(rng);
  return v;
}

double OrderedEnergy(const std::vector<float>& v) {
  double e = 0;
  for (float x : v) e += double{x} * x;
  return e;
}

ColumnCodingParams Params(ColumnMode mode, WaveletFilter filter, double matrix_energy) {
  return {.width = kW,
          .height = kH,
          .filter = filter,
          .mode = mode,
          .target_error = 0.1,
          .matrix_energy = matrix_energy};
}

TEST(ColumnCodingTest, AColumnInsideItsBudgetKeepsNothingAtTheShallowestDepth) {
  std::mt19937 rng(7);
  for (const WaveletFilter filter : {WaveletFilter::kHaar, WaveletFilter::kLeGall53}) {
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<float> v = RandomColumn(rng);
      const double energy = OrderedEnergy(v);
      // E_ref such that the budget target²·E_ref is the column's energy
      // times a factor just above 1: everything fits.
      const double matrix_energy = energy * (1 + 1e-6) / (0.1 * 0.1);
      const ColumnCodingParams p = Params(ColumnMode::kAdaptive, filter, matrix_energy);
      const double budget = 0.01 * matrix_energy;
      // The definition: at depth 0 nothing is kept, so depth 0 is a best depth.
      ASSERT_EQ(CountForBudget(v, {}, budget), 0);
      CodedColumn c;
      CodeColumn(p, v, &c);
      EXPECT_EQ(c.depth, 0);
      EXPECT_TRUE(c.positions.empty());
      EXPECT_EQ(c.dropped_energy, energy);  // the ordered sum, to the bit
      EXPECT_LE(c.dropped_energy, budget);

      CodeColumn(Params(ColumnMode::kFull, filter, matrix_energy), v, &c);
      EXPECT_EQ(c.depth, MaxDepth(kW, kH));
      EXPECT_TRUE(c.positions.empty());
      EXPECT_LE(c.dropped_energy, budget);
    }
  }
}

TEST(ColumnCodingTest, AColumnJustOverItsBudgetKeepsSomething) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<float> v = RandomColumn(rng);
    const double energy = OrderedEnergy(v);
    const double matrix_energy = energy * (1 - 1e-6) / (0.1 * 0.1);
    CodedColumn c;
    CodeColumn(Params(ColumnMode::kAdaptive, WaveletFilter::kHaar, matrix_energy), v, &c);
    EXPECT_FALSE(c.positions.empty()) << "trial " << trial;
    EXPECT_LE(c.dropped_energy, 0.01 * matrix_energy);
  }
}

// Energy a column lost before coding (bounced light left out,
// worker/columns/column_bounces.h) is spent from its budget: the selection
// drops no more than budget − left_out, the dropped energy counts both, and
// a column that the budget fitted whole without it keeps something with it.
TEST(ColumnCodingTest, EnergyLeftOutIsSpentFromTheBudget) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<float> v = RandomColumn(rng);
    const double energy = OrderedEnergy(v);
    const double matrix_energy = energy * 3 / (0.1 * 0.1);  // budget: three times the energy
    const double budget = 0.01 * matrix_energy;
    const ColumnCodingParams p = Params(ColumnMode::kAdaptive, WaveletFilter::kHaar, matrix_energy);
    CodedColumn whole, spent;
    CodeColumn(p, v, &whole);
    EXPECT_TRUE(whole.positions.empty());
    const double left_out = budget - 0.5 * energy;
    CodeColumn(p, v, &spent, left_out);
    EXPECT_FALSE(spent.positions.empty()) << "trial " << trial;
    EXPECT_GE(spent.dropped_energy, left_out);
    EXPECT_LE(spent.dropped_energy, budget);
    EXPECT_LE(spent.dropped_energy - left_out, 0.5 * energy);
  }
}

// A column whose smooth part a deep transform packs into few coefficients,
// plus sparse spikes that it smears.
std::vector<float> MixedColumn(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0, 1);
  const float smooth = u(rng), spikes = u(rng);
  std::vector<float> v(kW * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      v[y * kW + x] = smooth * (1 + std::sin(0.3f * x + 0.5f * y)) +
                      (u(rng) < 0.2f ? spikes * 4 * u(rng) : 0.0f);
  return v;
}

void ExpectSameCoding(const CodedColumn& a, const CodedColumn& b, int trial) {
  EXPECT_EQ(a.depth, b.depth) << "trial " << trial;
  EXPECT_EQ(a.positions, b.positions) << "trial " << trial;
  EXPECT_EQ(a.values, b.values) << "trial " << trial;
  EXPECT_EQ(a.dropped_energy, b.dropped_energy) << "trial " << trial;
  EXPECT_EQ(a.max_abs, b.max_abs) << "trial " << trial;
  EXPECT_EQ(a.step_unit, b.step_unit) << "trial " << trial;
  EXPECT_EQ(a.min_bits, b.min_bits) << "trial " << trial;
}

// The depth-0 alternative (adaptive by size, core/columns/group_codings.h)
// is exactly `2d`'s coding of the column, and asking for it leaves the
// fewest-coefficient coding as it was; a column already at depth 0 has none.
TEST(ColumnCodingTest, TheDepthZeroAlternativeIsTheTwoDCoding) {
  std::mt19937 rng(4);
  int deep = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const std::vector<float> v = MixedColumn(rng);
    ColumnCodingParams p = Params(ColumnMode::kAdaptive, WaveletFilter::kHaar, OrderedEnergy(v));
    p.target_error = 0.05;
    CodedColumn fewest, flat, alone, two_d;
    CodeColumn(p, v, &fewest, 0.0, &flat);
    CodeColumn(p, v, &alone);
    ExpectSameCoding(fewest, alone, trial);
    if (fewest.depth == 0) {
      EXPECT_EQ(flat.depth, -1) << "trial " << trial;
      continue;
    }
    ++deep;
    p.mode = ColumnMode::k2d;
    CodeColumn(p, v, &two_d);
    ExpectSameCoding(flat, two_d, trial);
    EXPECT_GT(flat.positions.size(), fewest.positions.size()) << "trial " << trial;
  }
  EXPECT_GT(deep, 10);
}

// CodeColumnAtDepth (an update's recomputed column at its old depth) at the
// depth the search chose is the search's coding, with and without a fill of
// uncovered cells, and with energy left out before coding (bounced light not
// added, worker/columns/column_bounces.h) spent from the budget alike.
TEST(ColumnCodingTest, CodingAtTheSearchedDepthIsTheSearchsCoding) {
  std::vector<int32_t> grid(kW * kH, -1);  // the left half and a diagonal covered
  for (int i = 0; i < kW * kH; ++i)
    if (i % kW < kW / 2 || i % kW == i / kW) grid[i] = i;
  const CellFiller filler(UncoveredFill::kPushPull, grid, kW, kH);
  std::mt19937 rng(5);
  std::vector<int> depths(MaxDepth(kW, kH) + 1, 0);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<float> v = MixedColumn(rng);
    ColumnCodingParams p = Params(ColumnMode::kAdaptive, WaveletFilter::kHaar, OrderedEnergy(v));
    p.target_error = 0.05;
    if (trial % 2 == 1) {
      for (int i = 0; i < kW * kH; ++i)
        if (grid[i] < 0) v[i] = 0;  // as staged
      p.filler = &filler;
    }
    const double left_out =
        trial % 3 == 2 ? 0.3 * p.target_error * p.target_error * p.matrix_energy : 0.0;
    CodedColumn searched, at;
    CodeColumn(p, v, &searched, left_out);
    CodeColumnAtDepth(p, v, searched.depth, &at, left_out);
    ExpectSameCoding(searched, at, trial);
    EXPECT_GE(at.dropped_energy, left_out) << "trial " << trial;
    ++depths[searched.depth];
  }
  EXPECT_GT(depths[0], 0);
  EXPECT_GT(depths.back() + depths[depths.size() - 2], 0);
}

// At any other depth the coding meets the same budget, measured by an
// independent oracle (the inverse transform of the kept coefficients against
// the column), and keeps no fewer coefficients than the search's.
TEST(ColumnCodingTest, CodingAtAnyDepthMeetsTheBudget) {
  std::mt19937 rng(6);
  for (int trial = 0; trial < 40; ++trial) {
    const std::vector<float> v = MixedColumn(rng);
    ColumnCodingParams p = Params(ColumnMode::kAdaptive, WaveletFilter::kHaar, OrderedEnergy(v));
    p.target_error = 0.05;
    const double budget = p.target_error * p.target_error * p.matrix_energy;
    CodedColumn searched;
    CodeColumn(p, v, &searched);
    for (int d = 0; d <= MaxDepth(kW, kH); ++d) {
      CodedColumn at;
      CodeColumnAtDepth(p, v, d, &at);
      EXPECT_EQ(at.depth, d);
      EXPECT_GE(at.positions.size(), searched.positions.size()) << "trial " << trial << " d " << d;
      std::vector<float> kept(v.size(), 0.0f);
      for (size_t k = 0; k < at.positions.size(); ++k) kept[at.positions[k]] = at.values[k];
      Inverse2d(p.filter, kept, kW, kH, d);
      double error = 0;
      for (size_t i = 0; i < v.size(); ++i) error += (double{v[i]} - kept[i]) * (v[i] - kept[i]);
      EXPECT_LE(error, budget * (1 + 1e-4)) << "trial " << trial << " d " << d;
      EXPECT_NEAR(error, at.dropped_energy, 1e-4 * budget) << "trial " << trial << " d " << d;
    }
  }
}

}  // namespace
}  // namespace wavebake
