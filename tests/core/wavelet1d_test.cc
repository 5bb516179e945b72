// 1D steps: orthogonality of the Haar and periodic Daubechies-4 analysis
// matrices, vanishing moments of the lifting filters, and the √2 gain
// normalization shared by all filters (core/wavelets/wavelet1d.h).
#include "core/wavelets/wavelet1d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/core/wavelet_test_util.h"

namespace wavebake {
namespace {

using testing::kAllFilters;

// Column j of the analysis matrix = forward step of the unit vector e_j.
std::vector<std::vector<float>> AnalysisColumns(WaveletFilter f, int n) {
  std::vector<std::vector<float>> cols(n, std::vector<float>(n, 0.0f));
  std::vector<float> scratch(n);
  for (int j = 0; j < n; ++j) {
    cols[j][j] = 1;
    Forward1d(f, cols[j], scratch);
  }
  return cols;
}

TEST(Wavelet1dTest, HaarAndDaub4AnalysisMatricesAreOrthogonal) {
  for (const WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kDaub4}) {
    for (const int n : {2, 4, 8, 16}) {
      const auto cols = AnalysisColumns(f, n);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          EXPECT_NEAR(testing::Dot(cols[i], cols[j]), i == j ? 1.0 : 0.0, 1e-6)
              << testing::FilterName(f) << " n=" << n;
        }
      }
    }
  }
}

TEST(Wavelet1dTest, Daub4TapsHaveTwoVanishingMomentsInTheInterior) {
  // Periodic D4 annihilates constants and ramps where the 4 taps do not wrap.
  const int n = 32;
  std::vector<float> line(n), scratch(n);
  for (int i = 0; i < n; ++i) line[i] = 2.0f * i - 5;
  Forward1d(WaveletFilter::kDaub4, line, scratch);
  for (int i = 0; i < n / 2 - 1; ++i) EXPECT_NEAR(line[n / 2 + i], 0.0, 1e-4) << i;
  EXPECT_GT(std::fabs(line[n - 1]), 1.0f);  // the wrapped pair sees the jump
}

TEST(Wavelet1dTest, GainsAreSqrtTwoForEveryFilter) {
  // DC gain of the lowpass and Nyquist gain of the highpass (interior).
  const int n = 32;
  for (const WaveletFilter f : kAllFilters) {
    std::vector<float> dc(n, 1.0f), nyq(n), scratch(n);
    for (int i = 0; i < n; ++i) nyq[i] = i % 2 ? -1.0f : 1.0f;
    Forward1d(f, dc, scratch);
    Forward1d(f, nyq, scratch);
    for (int i = 4; i < n / 2 - 4; ++i) {
      EXPECT_NEAR(dc[i], M_SQRT2, 2e-6) << testing::FilterName(f);
      EXPECT_NEAR(dc[n / 2 + i], 0.0, 2e-6) << testing::FilterName(f);
      EXPECT_NEAR(std::fabs(nyq[n / 2 + i]), M_SQRT2, 2e-6) << testing::FilterName(f);
      EXPECT_NEAR(nyq[i], 0.0, 2e-6) << testing::FilterName(f);
    }
  }
}

std::vector<float> Polynomial(int n, int degree) {
  std::vector<float> line(n);
  for (int i = 0; i < n; ++i) {
    const double t = (i - n / 2) / 8.0;
    line[i] = static_cast<float>(std::pow(t, degree) + 0.5 * t + 1);
  }
  return line;
}

// Largest interior highpass magnitude (support fully inside: pairs 2..h−3).
double InteriorHighpass(WaveletFilter f, std::vector<float> line) {
  const int n = static_cast<int>(line.size()), h = n / 2;
  std::vector<float> scratch(n);
  Forward1d(f, line, scratch);
  double m = 0;
  for (int i = 2; i < h - 3; ++i) m = std::max(m, std::fabs(double(line[h + i])));
  return m;
}

TEST(Wavelet1dTest, LiftingVanishingMoments) {
  // LeGall 5/3 has 2 vanishing moments, CDF 9/7 has 4: 9/7 annihilates cubics,
  // 5/3 annihilates ramps but not parabolas (so the check is not vacuous).
  const int n = 64;
  EXPECT_LT(InteriorHighpass(WaveletFilter::kLeGall53, Polynomial(n, 1)), 1e-5);
  EXPECT_LT(InteriorHighpass(WaveletFilter::kCdf97, Polynomial(n, 1)), 1e-5);
  EXPECT_LT(InteriorHighpass(WaveletFilter::kCdf97, Polynomial(n, 2)), 1e-5);
  EXPECT_LT(InteriorHighpass(WaveletFilter::kCdf97, Polynomial(n, 3)), 1e-4);
  EXPECT_GT(InteriorHighpass(WaveletFilter::kLeGall53, Polynomial(n, 2)), 1e-3);
}

TEST(Wavelet1dTest, LengthOneIsUntouchedAndLengthTwoReconstructs) {
  for (const WaveletFilter f : kAllFilters) {
    std::vector<float> one = {3.5f}, scratch(2);
    Forward1d(f, one, scratch);
    EXPECT_EQ(one[0], 3.5f);
    std::vector<float> two = {2.0f, -7.0f};
    Forward1d(f, two, scratch);
    // Every filter's 2-sample step has lowpass ∝ the sum, highpass ∝ the difference.
    EXPECT_NEAR(two[0], -5.0 * M_SQRT1_2, 1e-5) << testing::FilterName(f);
    Inverse1d(f, two, scratch);
    EXPECT_NEAR(two[0], 2.0, 1e-5);
    EXPECT_NEAR(two[1], -7.0, 1e-5);
  }
}

}  // namespace
}  // namespace wavebake
