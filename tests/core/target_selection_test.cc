#include "core/products/target_selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "core/products/haar_affine.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

struct Rect {
  double ax, bx, ay, by;
};

// The discrete transform of the rectangle's exact texel coverage: the basis
// is constant on texels, so coefficient / N is ∫ 1_R Ψ exactly.
std::vector<float> RectCoefficients(const Rect& r, int n) {
  std::vector<float> img(n * n);
  const auto cover = [n](double a, double b, int i) {
    return std::max(0.0, std::min(b, (i + 1.0) / n) - std::max(a, double(i) / n)) * n;
  };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      img[y * n + x] = static_cast<float>(cover(r.ax, r.bx, x) * cover(r.ay, r.by, y));
  Forward2d(WaveletFilter::kHaar, img, n, n, MaxDepth(n, n));
  return img;
}

// Does the support of basis function m (a dyadic square) meet the rectangle
// in a set of positive area?
bool SupportMeets(int m, int n, const Rect& r) {
  const FactorPair f = NonStandardFactors(m % n, m / n);
  const double w = std::ldexp(1.0, -f.x.level);
  const double x0 = f.x.offset * w, y0 = f.y.offset * w;
  return std::min(r.bx, x0 + w) > std::max(r.ax, x0) && std::min(r.by, y0 + w) > std::max(r.ay, y0);
}

const Rect kRects[] = {{0.1, 0.7, 0.3, 0.45},
                       {0, 1, 0, 1},
                       {0.25, 0.5, 0.5, 0.75},
                       {0.61, 0.99, 0.02, 0.9},
                       {0.4, 0.41, 0.4, 0.6}};

TEST(TargetSelection, PredictionIsTheConstantLightsCoefficient) {
  const int n = 16;
  TargetSelector sel(n);
  for (const Rect& r : kRects) {
    const std::vector<float> c = RectCoefficients(r, n);
    for (int m = 0; m < n * n; ++m)
      ASSERT_NEAR(sel.Prediction(r.ax, r.bx, r.ay, r.by, m), c[m] / n, 1e-6) << m;
  }
}

TEST(TargetSelection, AnUnboundedBudgetPicksExactlyTheTargetsThatMeetTheLight) {
  const int n = 32;
  TargetSelector sel(n);
  std::vector<uint16_t> out;
  for (const Rect& r : kRects) {
    sel.Select(r.ax, r.bx, r.ay, r.by, n * n, out);
    const std::set<int> chosen(out.begin(), out.end());
    EXPECT_EQ(chosen.size(), out.size());  // no repeats
    for (int m = 0; m < n * n; ++m) EXPECT_EQ(chosen.count(m) == 1, SupportMeets(m, n, r)) << m;
  }
  sel.Select(0.5, 0.5, 0.2, 0.8, n * n, out);
  EXPECT_TRUE(out.empty());  // an empty image lights nothing
}

// With a budget: its size, the largest predictions first, then the zero
// ones coarse level first — never a zero before a nonzero one.
TEST(TargetSelection, ABudgetKeepsTheLargestPredictionsThenTheCoarsestTies) {
  const int n = 32;
  TargetSelector sel(n);
  std::vector<uint16_t> out;
  for (const Rect& r : kRects) {
    for (int budget : {1, 5, 40, 150, 307}) {
      sel.Select(r.ax, r.bx, r.ay, r.by, budget, out);
      int meets = 0;
      for (int m = 0; m < n * n; ++m) meets += SupportMeets(m, n, r);
      ASSERT_EQ(static_cast<int>(out.size()), std::min(budget, meets));
      const std::set<int> chosen(out.begin(), out.end());
      double min_chosen = 1e30, max_left = 0;
      int finest_zero_chosen = -1, coarsest_zero_left = 99;
      for (int m = 0; m < n * n; ++m) {
        if (!SupportMeets(m, n, r)) continue;
        const double p = std::fabs(sel.Prediction(r.ax, r.bx, r.ay, r.by, m));
        const int level = NonStandardFactors(m % n, m / n).x.level;
        if (chosen.count(m)) {
          min_chosen = std::min(min_chosen, p);
          if (p < 1e-12) finest_zero_chosen = std::max(finest_zero_chosen, level);
        } else {
          max_left = std::max(max_left, p);
          if (p < 1e-12) coarsest_zero_left = std::min(coarsest_zero_left, level);
        }
      }
      EXPECT_GE(min_chosen, max_left * (1 - 1e-6)) << "budget " << budget;
      if (finest_zero_chosen >= 0) {
        EXPECT_LE(finest_zero_chosen, coarsest_zero_left);
      }
    }
  }
}

}  // namespace
}  // namespace wavebake
