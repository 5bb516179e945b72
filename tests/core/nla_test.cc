// Non-linear approximation against brute-force references: a full sort by
// (magnitude desc, index asc) and the definition of the budget rule.
#include "core/columns/nla.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace wavebake {
namespace {

// Values drawn from a few levels (so ties are common), some exact zeros.
std::vector<float> TieHeavy(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> level(-4, 4);
  std::vector<float> v(n);
  for (float& x : v) x = 0.25f * level(rng);
  return v;
}

std::vector<float> Smooth(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0, 1);
  std::vector<float> v(n);
  for (int i = 0; i < n; ++i) v[i] = g(rng) / (1 + 0.05f * i);  // decaying, like wavelet columns
  return v;
}

std::vector<float> Weights(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.5f, 1.5f);
  std::vector<float> w(n);
  for (float& x : w) x = u(rng);
  return w;
}

// Indices by decreasing |v w| in double, ties by lower index (the full order).
std::vector<uint32_t> BruteOrder(const std::vector<float>& v, const std::vector<float>& w) {
  std::vector<uint32_t> idx(v.size());
  std::iota(idx.begin(), idx.end(), 0u);
  auto mag = [&](uint32_t i) { return std::fabs(double(v[i]) * (w.empty() ? 1.0 : w[i])); };
  std::stable_sort(idx.begin(), idx.end(), [&](uint32_t a, uint32_t b) { return mag(a) > mag(b); });
  return idx;
}

double WeightedEnergy(const std::vector<float>& v, const std::vector<float>& w, uint32_t i) {
  const double x = double(v[i]) * (w.empty() ? 1.0 : w[i]);
  return x * x;
}

TEST(TopKTest, MatchesBruteForceSortIncludingTies) {
  for (const uint32_t seed : {1u, 2u, 3u}) {
    const std::vector<float> v = TieHeavy(500, seed);
    for (const bool weighted : {false, true}) {
      const std::vector<float> w = weighted ? Weights(500, seed + 10) : std::vector<float>{};
      const std::vector<uint32_t> order = BruteOrder(v, w);
      for (const int k : {0, 1, 7, 100, 500}) {
        const std::vector<uint32_t> top = TopK(v, w, k);
        EXPECT_EQ(top, std::vector<uint32_t>(order.begin(), order.begin() + k)) << k;
      }
    }
  }
}

TEST(TopKTest, ClampsK) {
  const std::vector<float> v = {1, -3, 2};
  EXPECT_EQ(TopK(v, {}, 10), (std::vector<uint32_t>{1, 2, 0}));
  EXPECT_TRUE(TopK(v, {}, -1).empty());
}

// The rule from its definition: walk the full order from the least important
// end, dropping while the running sum stays within budget.
std::vector<uint32_t> BruteSelect(const std::vector<float>& v, const std::vector<float>& w,
                                  double budget) {
  const std::vector<uint32_t> order = BruteOrder(v, w);
  size_t keep = order.size();
  double dropped = 0;
  while (keep > 0 && dropped + WeightedEnergy(v, w, order[keep - 1]) <= budget) {
    dropped += WeightedEnergy(v, w, order[--keep]);
  }
  std::vector<uint32_t> kept(order.begin(), order.begin() + keep);
  std::erase_if(kept, [&](uint32_t i) { return v[i] == 0; });
  std::sort(kept.begin(), kept.end());
  return kept;
}

TEST(SelectForBudgetTest, MatchesBruteForceRule) {
  for (const uint32_t seed : {4u, 5u, 6u}) {
    for (const bool ties : {false, true}) {
      const std::vector<float> v = ties ? TieHeavy(1000, seed) : Smooth(1000, seed);
      const std::vector<float> w = Weights(1000, seed + 1);
      double total = 0;
      for (uint32_t i = 0; i < v.size(); ++i) total += WeightedEnergy(v, w, i);
      for (const double frac : {0.0, 1e-4, 0.01, 0.1, 0.5, 0.999, 1.001, 2.0}) {
        const Selection sel = SelectForBudget(v, w, frac * total);
        EXPECT_EQ(sel.kept, BruteSelect(v, w, frac * total)) << "frac " << frac;
        EXPECT_EQ(CountForBudget(v, w, frac * total), static_cast<int>(sel.kept.size()));
      }
    }
  }
}

TEST(SelectForBudgetTest, WideDynamicRangeMatchesBruteForceRule) {
  // Magnitudes over 2^0..2^−120: far more binades than the implementation's
  // coarse bins (core/columns/nla.cc), so the cut can land in the catch-all lowest bin.
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> mant(1.0f, 2.0f);
  std::uniform_int_distribution<int> expo(-120, 0);
  std::vector<float> v(3000);
  for (float& x : v) x = std::ldexp(mant(rng), expo(rng)) * (rng() % 2 ? 1 : -1);
  double total = 0;
  for (float x : v) total += double(x) * x;
  for (const double frac : {1e-70, 1e-40, 1e-20, 1e-6, 0.3}) {
    EXPECT_EQ(SelectForBudget(v, {}, frac * total).kept, BruteSelect(v, {}, frac * total)) << frac;
    EXPECT_EQ(CountForBudget(v, {}, frac * total), int(BruteSelect(v, {}, frac * total).size()));
  }
}

TEST(SelectForBudgetTest, DroppedEnergyWithinBudgetAndSelectionMinimal) {
  const std::vector<float> v = Smooth(4096, 9);
  double total = 0;
  for (float x : v) total += double(x) * x;
  for (const double budget : {1e-3 * total, 0.05 * total, 0.3 * total}) {
    const Selection sel = SelectForBudget(v, {}, budget);
    // dropped_energy is the true energy outside the kept set...
    std::vector<bool> kept(v.size(), false);
    for (uint32_t i : sel.kept) kept[i] = true;
    double dropped = 0, least_kept = INFINITY;
    for (size_t i = 0; i < v.size(); ++i) {
      const double e = double(v[i]) * v[i];
      if (kept[i])
        least_kept = std::min(least_kept, e);
      else
        dropped += e;
    }
    EXPECT_NEAR(sel.dropped_energy, dropped, 1e-9 * total);
    EXPECT_LE(sel.dropped_energy, budget);
    // ...and no smaller set works: also dropping the weakest kept one exceeds it.
    EXPECT_GT(dropped + least_kept, budget);
    EXPECT_TRUE(std::is_sorted(sel.kept.begin(), sel.kept.end()));
  }
}

TEST(SelectForBudgetTest, EdgeBudgets) {
  const std::vector<float> v = {0, 3, 0, -1, 2};
  // Budget 0 keeps exactly the nonzeros; a budget ≥ total keeps nothing.
  EXPECT_EQ(SelectForBudget(v, {}, 0).kept, (std::vector<uint32_t>{1, 3, 4}));
  EXPECT_TRUE(SelectForBudget(v, {}, 14).kept.empty());
  EXPECT_DOUBLE_EQ(SelectForBudget(v, {}, 14).dropped_energy, 14);
  // 1 (the −1) fits in 1.5, 1 + 4 does not.
  const Selection s = SelectForBudget(v, {}, 1.5);
  EXPECT_EQ(s.kept, (std::vector<uint32_t>{1, 4}));
  EXPECT_DOUBLE_EQ(s.dropped_energy, 1);
  // The rule is ≤: a budget exactly equal to the tail's energy lets it go.
  EXPECT_EQ(SelectForBudget(v, {}, 1.0).kept, (std::vector<uint32_t>{1, 4}));
  EXPECT_EQ(SelectForBudget(v, {}, 5.0).kept, (std::vector<uint32_t>{1}));
  EXPECT_EQ(CountForBudget(v, {}, 5.0), 1);
  EXPECT_EQ(SelectForBudget(v, {}, -1).kept.size(), 3u);
  EXPECT_TRUE(SelectForBudget(std::vector<float>{}, {}, 0).kept.empty());
}

TEST(SelectForBudgetTest, WeightsActAsEnergyScale) {
  // Uniform weight 2 quadruples every energy: same as budget / 4 unweighted.
  const std::vector<float> v = Smooth(2000, 3);
  const std::vector<float> w(v.size(), 2.0f);
  for (const double budget : {0.01, 0.5, 3.0}) {
    EXPECT_EQ(SelectForBudget(v, w, budget).kept, SelectForBudget(v, {}, budget / 4).kept);
  }
}

TEST(SelectForBudgetTest, TiesKeepLowerIndices) {
  const std::vector<float> v(10, 1.0f);
  // Budget 3.5 lets three of the ten equal entries go: the three highest indices.
  const Selection s = SelectForBudget(v, {}, 3.5);
  EXPECT_EQ(s.kept, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6}));
  // Exactly 3.0 still lets three go (the rule is ≤).
  EXPECT_EQ(SelectForBudget(v, {}, 3.0).kept, s.kept);
  EXPECT_EQ(CountForBudget(v, {}, 3.0), 7);
}

TEST(SelectForBudgetTest, KeptSetIsATopKPrefix) {
  const std::vector<float> v = Smooth(65536, 12);
  const std::vector<float> w = Weights(65536, 13);
  const int count = CountForBudget(v, w, 1.0);
  ASSERT_GT(count, 0);
  std::vector<uint32_t> top = TopK(v, w, count);
  std::sort(top.begin(), top.end());
  EXPECT_EQ(SelectForBudget(v, w, 1.0).kept, top);
}

}  // namespace
}  // namespace wavebake
