// Perfect reconstruction, orthonormality and the step contract of every 2D
// filter (DESIGN.md §1 "Row transform", "Column transform"; 4D paper Eq. 5).
#include "core/wavelets/wavelet2d.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/wavelet_test_util.h"

namespace wavebake {
namespace {

using testing::kAllFilters;
using testing::MaxAbs;
using testing::MaxAbsDiff;
using testing::RandomImage;

struct Shape {
  int w, h;
};
// Square, non-square both ways, degenerate 1-wide, and the 2-long edge cases.
constexpr Shape kShapes[] = {{1, 1},  {2, 2}, {4, 4}, {8, 2},   {2, 16},  {32, 8},
                             {8, 32}, {4, 1}, {1, 4}, {16, 16}, {64, 64}, {128, 32}};

// Float lifting of 9/7 costs a few ulps per step; 2e-6 of the largest value
// is well above that and far below any real reconstruction bug.
constexpr double kPrTol = 2e-6;

class FilterTest : public ::testing::TestWithParam<WaveletFilter> {};

TEST(MaxDepthTest, IsLog2OfTheSmallerSide) {
  EXPECT_EQ(MaxDepth(1, 1), 0);
  EXPECT_EQ(MaxDepth(2, 2), 1);
  EXPECT_EQ(MaxDepth(8, 2), 1);
  EXPECT_EQ(MaxDepth(2, 16), 1);
  EXPECT_EQ(MaxDepth(32, 8), 3);
  EXPECT_EQ(MaxDepth(256, 256), 8);
  EXPECT_EQ(MaxDepth(1, 64), 0);
}

TEST_P(FilterTest, PerfectReconstructionAllShapesAllDepths) {
  const WaveletFilter f = GetParam();
  for (const Shape s : kShapes) {
    for (int d = 0; d <= MaxDepth(s.w, s.h); ++d) {
      const std::vector<float> orig = RandomImage(s.w, s.h, 17 + d);
      std::vector<float> img = orig;
      Forward2d(f, img, s.w, s.h, d);
      if (d > 0) {
        EXPECT_GT(MaxAbsDiff(img, orig), 1e-3) << "transform did nothing";
      }
      Inverse2d(f, img, s.w, s.h, d);
      EXPECT_LE(MaxAbsDiff(img, orig), kPrTol * MaxAbs(orig)) << s.w << "x" << s.h << " d=" << d;
    }
  }
}

TEST_P(FilterTest, StepByStepReconstructsAfterEveryStep) {
  const WaveletFilter f = GetParam();
  for (const Shape s : {Shape{32, 8}, Shape{2, 16}, Shape{16, 16}}) {
    const std::vector<float> orig = RandomImage(s.w, s.h, 5);
    std::vector<float> img = orig;
    const int dmax = MaxDepth(s.w, s.h);
    for (int step = 0; step < dmax; ++step) ForwardStep(f, img, s.w, s.h, step);
    for (int step = dmax - 1; step >= 0; --step) {
      // Undo one step at a time and check against a fresh forward to `step`.
      InverseStep(f, img, s.w, s.h, step);
      std::vector<float> ref = orig;
      Forward2d(f, ref, s.w, s.h, step);
      EXPECT_LE(MaxAbsDiff(img, ref), kPrTol * MaxAbs(orig)) << s.w << "x" << s.h;
    }
  }
}

TEST_P(FilterTest, WholeDepthEqualsSequenceOfSingleSteps) {
  const WaveletFilter f = GetParam();
  const int w = 32, h = 8, d = MaxDepth(w, h);
  const std::vector<float> orig = RandomImage(w, h, 9);
  std::vector<float> whole = orig, steps = orig;
  Forward2d(f, whole, w, h, d);
  for (int s = 0; s < d; ++s) ForwardStep(f, steps, w, h, s);
  EXPECT_EQ(whole, steps);
  Inverse2d(f, whole, w, h, d);
  for (int s = d - 1; s >= 0; --s) InverseStep(f, steps, w, h, s);
  EXPECT_EQ(whole, steps);
}

TEST_P(FilterTest, StepTouchesOnlyItsBlock) {
  const WaveletFilter f = GetParam();
  const int w = 16, h = 8;
  const std::vector<float> orig = RandomImage(w, h, 3);
  std::vector<float> img = orig;
  ForwardStep(f, img, w, h, 1);  // block 8×4
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (x < 8 && y < 4) continue;
      EXPECT_EQ(img[y * w + x], orig[y * w + x]) << x << "," << y;
    }
  }
}

TEST_P(FilterTest, ConstantImageHasOnlyScalingCoefficients) {
  // DC gain √2 per 1D step (core/wavelets/wavelet1d.h) and a highpass that kills
  // constants: after d 2D steps every LL coefficient is c·2^d, all else 0.
  const WaveletFilter f = GetParam();
  for (const Shape s : {Shape{16, 16}, Shape{32, 8}, Shape{2, 2}}) {
    const int d = MaxDepth(s.w, s.h);
    const float c = 0.7f;
    std::vector<float> img(s.w * s.h, c);
    Forward2d(f, img, s.w, s.h, d);
    const int lw = s.w >> d, lh = s.h >> d;
    for (int y = 0; y < s.h; ++y) {
      for (int x = 0; x < s.w; ++x) {
        const double expected = (x < lw && y < lh) ? c * std::ldexp(1.0, d) : 0.0;
        EXPECT_NEAR(img[y * s.w + x], expected, 1e-5 * c * s.w) << x << "," << y;
      }
    }
  }
}

TEST_P(FilterTest, ImpulseReconstructs) {
  const WaveletFilter f = GetParam();
  for (const Shape s : {Shape{8, 8}, Shape{32, 8}, Shape{2, 2}}) {
    for (const int pos : {0, s.w * s.h - 1, s.w * s.h / 2 + 1}) {
      std::vector<float> img(s.w * s.h, 0.0f);
      img[pos] = 1;
      const std::vector<float> orig = img;
      const int d = MaxDepth(s.w, s.h);
      Forward2d(f, img, s.w, s.h, d);
      Inverse2d(f, img, s.w, s.h, d);
      EXPECT_LE(MaxAbsDiff(img, orig), kPrTol);
    }
  }
}

TEST_P(FilterTest, LinearRampHasZeroInteriorDetailsOnlyBeyondHaar) {
  // Daubechies-4, LeGall 5/3 and CDF 9/7 have ≥ 2 vanishing moments: a plane
  // a·x + b·y + c gives zero HL/LH/HH wherever the filter support stays inside
  // the image (the symmetric/periodic extension bends the ramp at the border).
  // Haar has one vanishing moment: its HL and LH of a ramp are nonzero (its
  // HH, a mixed difference, still kills any a·x + b·y + c).
  const WaveletFilter f = GetParam();
  const bool haar = f == WaveletFilter::kHaar;
  const int n = 64, h = n / 2;
  std::vector<float> img(n * n);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) img[y * n + x] = 0.25f * x - 0.5f * y + 3;
  }
  const double scale = MaxAbs(img);
  ForwardStep(f, img, n, n, 0);
  const int margin = 4;  // 9/7 highpass reaches 2 samples (1 pair) left, 4 (2 pairs) right
  int checked = 0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const bool hx = x >= h, hy = y >= h;
      if (!hx && !hy) continue;
      const int ix = x % h, iy = y % h;
      if (ix < margin || ix >= h - margin || iy < margin || iy >= h - margin) continue;
      if (haar && !(hx && hy)) {
        EXPECT_GT(std::fabs(img[y * n + x]), 0.1) << x << "," << y;
      } else {
        EXPECT_NEAR(img[y * n + x], 0.0, 2e-6 * scale) << x << "," << y;
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3 * (h - 2 * margin) * (h - 2 * margin));
}

std::vector<float> Transposed(const std::vector<float>& img, int w, int h) {
  std::vector<float> t(img.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) t[x * h + y] = img[y * w + x];
  }
  return t;
}

TEST_P(FilterTest, RowAndColumnPassesApplyTheSameFilter) {
  // Rows and columns go through different code (1D line kernels vs. gathered
  // or row-vector column passes). A separable step must commute with
  // transposition: F(Xᵀ) = F(X)ᵀ (HL and LH trade places, as they should).
  const WaveletFilter f = GetParam();
  for (const Shape s : {Shape{32, 8}, Shape{16, 16}, Shape{2, 8}}) {
    const std::vector<float> orig = RandomImage(s.w, s.h, 23);
    for (int d = 1; d <= MaxDepth(s.w, s.h); ++d) {
      std::vector<float> a = orig, b = Transposed(orig, s.w, s.h);
      Forward2d(f, a, s.w, s.h, d);
      Forward2d(f, b, s.h, s.w, d);
      EXPECT_LE(MaxAbsDiff(Transposed(a, s.w, s.h), b), 2e-6) << s.w << "x" << s.h << " d=" << d;
    }
  }
}

TEST_P(FilterTest, ForwardIsLinear) {
  const WaveletFilter f = GetParam();
  const int w = 32, h = 16, d = MaxDepth(w, h);
  std::vector<float> a = RandomImage(w, h, 1), b = RandomImage(w, h, 2), ab(w * h);
  for (int i = 0; i < w * h; ++i) ab[i] = 2 * a[i] - 3 * b[i];
  Forward2d(f, a, w, h, d);
  Forward2d(f, b, w, h, d);
  Forward2d(f, ab, w, h, d);
  for (int i = 0; i < w * h; ++i) EXPECT_NEAR(ab[i], 2 * a[i] - 3 * b[i], 1e-5);
}

INSTANTIATE_TEST_SUITE_P(AllFilters, FilterTest, ::testing::ValuesIn(kAllFilters),
                         [](const auto& info) { return testing::FilterName(info.param); });

// Orthonormal filters (Haar, periodic Daubechies-4): the transform is an
// orthogonal matrix, so norms and dot products survive at every depth.
class OrthonormalTest : public ::testing::TestWithParam<WaveletFilter> {};

TEST_P(OrthonormalTest, PreservesEnergyAndDotProducts) {
  const WaveletFilter f = GetParam();
  for (const Shape s : {Shape{16, 16}, Shape{32, 8}, Shape{2, 16}, Shape{2, 2}}) {
    for (int d = 0; d <= MaxDepth(s.w, s.h); ++d) {
      std::vector<float> a = RandomImage(s.w, s.h, 11), b = RandomImage(s.w, s.h, 12);
      const double aa = testing::Dot(a, a), ab = testing::Dot(a, b);
      Forward2d(f, a, s.w, s.h, d);
      Forward2d(f, b, s.w, s.h, d);
      EXPECT_NEAR(testing::Dot(a, a), aa, 1e-5 * aa);
      EXPECT_NEAR(testing::Dot(a, b), ab, 1e-5 * aa);
    }
  }
}

TEST_P(OrthonormalTest, BasisFunctionsAreOrthonormal) {
  // Synthesis basis functions = inverse transforms of unit impulses; their Gram
  // matrix must be the identity.
  const WaveletFilter f = GetParam();
  const int w = 8, h = 4, d = MaxDepth(w, h), n = w * h;
  std::vector<std::vector<float>> basis(n, std::vector<float>(n, 0.0f));
  for (int i = 0; i < n; ++i) {
    basis[i][i] = 1;
    Inverse2d(f, basis[i], w, h, d);
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      EXPECT_NEAR(testing::Dot(basis[i], basis[j]), i == j ? 1.0 : 0.0, 1e-6) << i << "," << j;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Orthonormal, OrthonormalTest,
                         ::testing::Values(WaveletFilter::kHaar, WaveletFilter::kDaub4),
                         [](const auto& info) { return testing::FilterName(info.param); });

}  // namespace
}  // namespace wavebake
