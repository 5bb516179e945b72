// The adaptive depth search against its definition (DESIGN.md §1; 4D paper
// §4.2): transform to every depth, count exactly with core/columns/nla.h, keep the
// smallest count (ties: shallower). The search's shortcut — histogram bounds
// on the count, exact counts only where they decide — must pick the same
// depth, and the bounds must bracket the exact count.
#include "core/columns/depth_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/columns/count_bounds.h"
#include "core/columns/nla.h"
#include "core/wavelets/subband.h"
#include "core/wavelets/wavelet2d.h"
#include "tests/testing/synthetic_columns.h"

namespace wavebake {
namespace {

// Values spread over many binades, with zeros and exact ties.
std::vector<float> SpreadValues(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<float> v(n);
  for (float& x : v) {
    const double r = unit(rng);
    if (r < 0.1)
      x = 0;
    else if (r < 0.2)
      x = 0.25f;  // ties
    else
      x = float((unit(rng) < 0.5 ? -1 : 1) * std::exp(-20 * unit(rng)));
  }
  return v;
}

TEST(CountBoundsTest, BracketTheExactCount) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + int(unit(rng) * 3000);
    const std::vector<float> v = SpreadValues(rng, n);
    std::vector<float> w;
    if (trial % 3 == 0) {
      for (int i = 0; i < n; ++i) w.push_back(float(0.5 + unit(rng)));
    }
    double total = 0;
    for (int i = 0; i < n; ++i) total += std::pow(double(v[i]) * (w.empty() ? 1 : w[i]), 2);
    const double budget = trial % 10 == 0 ? 0.0 : total * std::pow(10.0, -6 * unit(rng));
    EnergyHistogram h(budget);
    // Built with a detour through adds and removes, as the search does.
    const std::vector<float> noise = SpreadValues(rng, n);
    h.Add(noise, w);
    h.Add(v, w);
    h.Remove(noise, w);
    const CountBounds b = h.Bounds();
    const int exact = CountForBudget(v, w, budget);
    EXPECT_LE(b.lower, exact) << "trial " << trial;
    EXPECT_GE(b.upper, exact) << "trial " << trial;
  }
}

// The reference search: every depth, exact counts.
int ReferenceDepth(const ColumnCodingParams& p, const std::vector<float>& image, double budget) {
  int best_depth = 0, best_count = 0;
  for (int d = 0; d <= MaxDepth(p.width, p.height); ++d) {
    std::vector<float> c = image;
    Forward2d(p.filter, c, p.width, p.height, d);
    std::span<const float> w;
    if (d > 0 && p.filter != WaveletFilter::kHaar)
      w = SynthesisNormsRef(p.filter, p.width, p.height, d);
    const int count = CountForBudget(c, w, budget);
    if (d == 0 || count < best_count) best_depth = d, best_count = count;
  }
  return best_depth;
}

TEST(DepthSearchTest, PicksTheSameDepthAsCountingEveryDepth) {
  const int w = 32, h = 16;  // non-square: block extents differ per axis
  const auto image_of = test_support::SyntheticMatrix(w, h);
  std::mt19937 rng(11);
  int checked = 0, not_extreme = 0;
  for (WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kLeGall53, WaveletFilter::kCdf97}) {
    for (double target : {0.003, 0.03, 0.2}) {
      ColumnCodingParams p{.width = w,
                           .height = h,
                           .filter = f,
                           .mode = ColumnMode::kAdaptive,
                           .target_error = target};
      for (int m = 0; m < 64; ++m) {
        std::vector<float> image(w * h);
        for (int i = 0; i < w * h; ++i) image[i] = image_of(m, i % w, i / w);
        if (m % 8 == 7) image = SpreadValues(rng, w * h);
        double energy = 0;
        for (float x : image) energy += double(x) * x;
        if (energy == 0) continue;
        const double budget = target * target * energy;
        const int reference = ReferenceDepth(p, image, budget);
        const DepthChoice got = ChooseDepth(p, image, budget);
        ASSERT_EQ(got.depth, reference)
            << "filter " << int(f) << " target " << target << " m " << m;
        // The coefficients handed back are that depth's layout.
        std::vector<float> expected = image;
        Forward2d(f, expected, w, h, reference);
        EXPECT_TRUE(std::equal(expected.begin(), expected.end(), got.coefficients.begin()));
        ++checked;
        not_extreme += reference != 0 && reference != MaxDepth(w, h);
      }
    }
  }
  EXPECT_GT(checked, 400);
  EXPECT_GT(not_extreme, 20);  // intermediate depths are rebuilt from saved blocks
}

}  // namespace
}  // namespace wavebake
