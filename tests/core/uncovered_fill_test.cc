// Fills of uncovered grid cells (core/columns/uncovered_fill.h), checked against
// what each fill promises: covered cells untouched, Haar details of
// uncovered blocks exactly zero (push-pull), copies of a nearest covered
// cell (dilation), and free coefficients that change no covered cell.
#include "core/columns/uncovered_fill.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

constexpr int kW = 16, kH = 16;

// A disk of covered cells plus a lone cell and a thin diagonal: charts of
// several shapes; values random.
struct Case {
  std::vector<int32_t> grid;
  std::vector<float> values;
};

Case MakeCase() {
  Case c;
  c.grid.assign(kW * kH, -1);
  int32_t id = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool disk = (x - 5) * (x - 5) + (y - 6) * (y - 6) <= 12;
      const bool diagonal = x == y + 6 && x >= 10;
      if (disk || diagonal || (x == 13 && y == 1)) c.grid[y * kW + x] = id++;
    }
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 2);
  c.values.resize(kW * kH);
  for (int i = 0; i < kW * kH; ++i) c.values[i] = c.grid[i] >= 0 ? u(rng) : NAN;
  return c;
}

int Chebyshev(int a, int b) {
  return std::max(std::abs(a % kW - b % kW), std::abs(a / kW - b / kW));
}

TEST(CellFiller, CoveredCellsAreLeftAlone) {
  const Case c = MakeCase();
  for (UncoveredFill kind :
       {UncoveredFill::kZero, UncoveredFill::kPushPull, UncoveredFill::kDilate}) {
    std::vector<float> v = c.values;
    CellFiller(kind, c.grid, kW, kH).Fill(v);
    for (int i = 0; i < kW * kH; ++i) {
      if (c.grid[i] >= 0) {
        EXPECT_EQ(v[i], c.values[i]) << i;
      } else {
        EXPECT_TRUE(std::isfinite(v[i])) << "kind " << int(kind) << " cell " << i;
      }
    }
  }
}

TEST(CellFiller, PushPullMakesHaarDetailsOfUncoveredBlocksZero) {
  const Case c = MakeCase();
  std::vector<float> v = c.values;
  const CellFiller filler(UncoveredFill::kPushPull, c.grid, kW, kH);
  filler.Fill(v);
  // Finest step: each 2×2 block with no covered cell is constant, so its
  // three details are exactly 0; a block with some covered cells has its
  // uncovered cells at the mean of the covered ones.
  for (int by = 0; by < kH; by += 2)
    for (int bx = 0; bx < kW; bx += 2) {
      double sum = 0;
      int n = 0;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx)
          if (c.grid[(by + dy) * kW + bx + dx] >= 0) sum += c.values[(by + dy) * kW + bx + dx], ++n;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const int i = (by + dy) * kW + bx + dx;
          if (c.grid[i] >= 0) continue;
          if (n > 0) {
            EXPECT_NEAR(v[i], sum / n, 1e-6) << i;
          } else {
            EXPECT_EQ(v[i], v[by * kW + bx]) << i;
          }
        }
    }
  std::vector<float> coeffs = v;
  Forward2d(WaveletFilter::kHaar, coeffs, kW, kH, MaxDepth(kW, kH));
  std::vector<float> zeroed = coeffs;
  filler.ZeroUncoveredCoefficients(zeroed, MaxDepth(kW, kH));
  for (int i = 0; i < kW * kH; ++i) {
    if (zeroed[i] == 0) {
      EXPECT_EQ(coeffs[i], 0) << "a free detail at " << i << " was not zero";
    }
  }
}

TEST(CellFiller, DilationCopiesANearestCoveredCell) {
  const Case c = MakeCase();
  for (int limit : {2, 1000}) {
    std::vector<float> v = c.values;
    CellFiller(UncoveredFill::kDilate, c.grid, kW, kH, limit).Fill(v);
    for (int i = 0; i < kW * kH; ++i) {
      if (c.grid[i] >= 0) continue;
      int nearest = 1 << 30;
      for (int j = 0; j < kW * kH; ++j)
        if (c.grid[j] >= 0) nearest = std::min(nearest, Chebyshev(i, j));
      if (nearest > limit) {
        EXPECT_TRUE(std::isnan(v[i])) << i;
        continue;
      }
      bool matches = false;
      for (int j = 0; j < kW * kH; ++j)
        matches = matches || (c.grid[j] >= 0 && Chebyshev(i, j) == nearest && v[i] == c.values[j]);
      EXPECT_TRUE(matches) << "cell " << i << " holds no value of a covered cell at distance "
                           << nearest;
    }
  }
}

TEST(CellFiller, FreeCoefficientsChangeNoCoveredCell) {
  const Case c = MakeCase();
  for (UncoveredFill kind : {UncoveredFill::kPushPull, UncoveredFill::kDilate}) {
    const CellFiller filler(kind, c.grid, kW, kH);
    for (int depth = 1; depth <= MaxDepth(kW, kH); ++depth) {
      std::vector<float> v = c.values;
      filler.Fill(v);
      Forward2d(WaveletFilter::kHaar, v, kW, kH, depth);
      filler.ZeroUncoveredCoefficients(v, depth);
      Inverse2d(WaveletFilter::kHaar, v, kW, kH, depth);
      for (int i = 0; i < kW * kH; ++i)
        if (c.grid[i] >= 0) {
          EXPECT_NEAR(v[i], c.values[i], 1e-5) << "depth " << depth << " cell " << i;
        }
    }
  }
}

}  // namespace
}  // namespace wavebake
