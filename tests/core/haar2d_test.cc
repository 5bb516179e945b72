// The non-standard 2D Haar transform against coefficients computed directly
// as inner products with the analytic Haar basis (Vollick & Lessig §2):
// a detail of step s at quadrant position (i, j) is ±2^−(s+1) on the square
// of side 2^(s+1) at (i·2^(s+1), j·2^(s+1)), with sign pattern + − along x
// (HL), along y (LH) or checkerboard (HH); the depth-d scaling function is
// 2^−d on a square of side 2^d.
#include "core/wavelets/haar2d.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/wavelets/separable2d.h"
#include "core/wavelets/wavelet2d.h"
#include "tests/core/wavelet_test_util.h"

namespace wavebake {
namespace {

using testing::MaxAbsDiff;
using testing::RandomImage;

// ⟨img, basis⟩ for a square support of side `side` at (x0, y0); `band`
// selects the sign pattern (0: all +, 1: left + right −, 2: top + bottom −,
// 3: both).
double HaarInnerProduct(const std::vector<float>& img, int width, int x0, int y0, int side,
                        int band) {
  double sum = 0;
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const int sx = (band & 1) && x >= side / 2 ? -1 : 1;
      const int sy = (band & 2) && y >= side / 2 ? -1 : 1;
      sum += sx * sy * double(img[(y0 + y) * width + x0 + x]);
    }
  }
  return sum / side;  // basis amplitude 1/side gives unit norm
}

void ExpectMatchesAnalyticBasis(int w, int h, int depth) {
  const std::vector<float> orig = RandomImage(w, h, w * 131 + h);
  std::vector<float> img = orig;
  HaarForward2d(img, w, h, depth);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // Find the step that produced (x, y) directly from the layout.
      int side = 1 << depth, x0 = x * side, y0 = y * side, band = 0;
      if (x >= (w >> depth) || y >= (h >> depth)) {
        // Smallest block (largest s) containing the point.
        int s = depth - 1;
        for (; s >= 0; --s) {
          if (x < (w >> s) && y < (h >> s)) break;
        }
        const int hw = w >> (s + 1), hh = h >> (s + 1);
        band = (x >= hw ? 1 : 0) + (y >= hh ? 2 : 0);
        side = 1 << (s + 1);
        x0 = (x % hw) * side;
        y0 = (y % hh) * side;
      }
      EXPECT_NEAR(img[y * w + x], HaarInnerProduct(orig, w, x0, y0, side, band), 1e-5)
          << w << "x" << h << " d=" << depth << " at " << x << "," << y;
    }
  }
}

TEST(Haar2dTest, CoefficientsAreInnerProductsWithAnalyticBasis) {
  ExpectMatchesAnalyticBasis(16, 16, 4);
  ExpectMatchesAnalyticBasis(16, 16, 2);
  ExpectMatchesAnalyticBasis(32, 8, 3);
  ExpectMatchesAnalyticBasis(4, 16, 2);
  ExpectMatchesAnalyticBasis(2, 2, 1);
}

TEST(Haar2dTest, ConstantImageGivesMeanTimesSqrtArea) {
  for (const int n : {1, 2, 8, 64}) {
    const float c = 0.375f;
    std::vector<float> img(n * n, c);
    HaarForward2d(img, n, n, MaxDepth(n, n));
    EXPECT_FLOAT_EQ(img[0], c * n);  // mean·√(W·H)
    for (int i = 1; i < n * n; ++i) EXPECT_EQ(img[i], 0.0f) << i;
  }
}

TEST(Haar2dTest, MatchesSeparableDriverWithOneDimensionalHaar) {
  // Two independent implementations of the same step: 2×2 cells vs. the
  // generic rows-then-columns driver over the 1D Haar kernel.
  for (const auto& [w, h] : {std::pair{32, 8}, std::pair{8, 8}, std::pair{2, 16}}) {
    const std::vector<float> orig = RandomImage(w, h, 77);
    for (int s = 0; s < MaxDepth(w, h); ++s) {
      std::vector<float> a = orig, b = orig;
      HaarForwardStep2d(a, w, h, s);
      SeparableForwardStep(WaveletFilter::kHaar, b, w, h, s);
      EXPECT_LE(MaxAbsDiff(a, b), 1e-6);
      HaarInverseStep2d(a, w, h, s);
      SeparableInverseStep(WaveletFilter::kHaar, b, w, h, s);
      EXPECT_LE(MaxAbsDiff(a, b), 1e-6);
    }
  }
}

TEST(Haar2dTest, OneWideBlockGetsOneDimensionalStep) {
  // A 1×4 image: only the y direction can be transformed.
  std::vector<float> img = {1, 3, 5, 11};
  HaarForwardStep2d(img, 1, 4, 0);
  const float r = static_cast<float>(M_SQRT1_2);
  EXPECT_FLOAT_EQ(img[0], 4 * r);
  EXPECT_FLOAT_EQ(img[1], 16 * r);
  EXPECT_FLOAT_EQ(img[2], -2 * r);
  EXPECT_FLOAT_EQ(img[3], -6 * r);
  HaarInverseStep2d(img, 1, 4, 0);
  EXPECT_NEAR(img[3], 11, 1e-6);
}

TEST(Haar2dTest, FullDepthFaceRoundTripIsExactForDyadicData) {
  // Dyadic rationals stay exact through ×½ and ± in float, so an integer face
  // reconstructs bit-exactly: a strong check on the 2×2 formulas.
  const int n = 32;
  std::vector<float> img(n * n);
  for (int i = 0; i < n * n; ++i) img[i] = static_cast<float>((i * 37) % 101 - 50);
  const std::vector<float> orig = img;
  HaarForward2d(img, n, n, MaxDepth(n, n));
  HaarInverse2d(img, n, n, MaxDepth(n, n));
  EXPECT_EQ(img, orig);
}

}  // namespace
}  // namespace wavebake
