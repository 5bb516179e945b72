#include "worker/tiles/row_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace wavebake {
namespace {

constexpr WaveletFilter kRowFilters[] = {WaveletFilter::kHaar, WaveletFilter::kDaub4};

std::vector<float> RandomRow(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<float> row(6 * n * n);
  for (float& v : row) v = u(rng);
  return row;
}

double SumOfSquares(const std::vector<float>& v) {
  return std::inner_product(v.begin(), v.end(), v.begin(), 0.0);
}

// Orthonormal filters (DESIGN.md §1): the transform preserves Σ v² (Parseval),
// and the inverse gives the row back.
TEST(RowTransformTest, OrthonormalAndInvertible) {
  for (WaveletFilter f : kRowFilters) {
    for (int n : {8, 16, 32}) {
      const std::vector<float> pixels = RandomRow(n, n);
      std::vector<float> row = pixels;
      RowTransform(f, n, row);
      EXPECT_NEAR(SumOfSquares(row), SumOfSquares(pixels), 1e-5 * SumOfSquares(pixels)) << n;
      InverseRowTransform(f, n, row);
      for (size_t m = 0; m < row.size(); ++m)
        ASSERT_NEAR(row[m], pixels[m], 1e-5f) << n << " " << m;
    }
  }
}

// Each face is transformed on its own: a row that is non-zero on one face
// stays zero on the other five, and the face's coefficients equal the ones
// of the same face inside a full row.
TEST(RowTransformTest, FacesAreIndependent) {
  const int n = 16, texels = n * n;
  const std::vector<float> full = RandomRow(n, 7);
  for (WaveletFilter f : kRowFilters) {
    std::vector<float> transformed = full;
    RowTransform(f, n, transformed);
    for (int face = 0; face < 6; ++face) {
      std::vector<float> alone(full.size(), 0.0f);
      std::copy_n(full.begin() + face * texels, texels, alone.begin() + face * texels);
      RowTransform(f, n, alone);
      for (int m = 0; m < static_cast<int>(alone.size()); ++m) {
        const bool inside = m / texels == face;
        ASSERT_EQ(alone[m], inside ? transformed[m] : 0.0f) << "face " << face << " m " << m;
      }
    }
  }
}

// Full depth, Mallat layout: the face's scaling coefficient sits at its texel
// (0, 0), m = face·N², and equals (Σ over the face)/N — each of the log2 N
// orthonormal 2D steps halves the sum of the low band. That holds for
// periodic Daubechies-4 too (its low-pass taps sum to 1/√2 per parity).
TEST(RowTransformTest, ScalingCoefficientIsFaceSumOverN) {
  for (WaveletFilter f : kRowFilters) {
    for (int n : {8, 32}) {
      const std::vector<float> pixels = RandomRow(n, 100 + n);
      std::vector<float> row = pixels;
      RowTransform(f, n, row);
      for (int face = 0; face < 6; ++face) {
        const auto first = pixels.begin() + face * n * n;
        const double sum = std::accumulate(first, first + n * n, 0.0);
        EXPECT_NEAR(row[face * n * n], sum / n, 1e-5) << "N=" << n << " face " << face;
      }
    }
  }
}

// A constant face is all scaling coefficient: every detail is exactly 0 for
// Haar and to rounding for Daubechies-4 (its high-pass taps sum to 0).
TEST(RowTransformTest, ConstantFaceHasNoDetails) {
  const int n = 16;
  for (WaveletFilter f : kRowFilters) {
    std::vector<float> row(6 * n * n);
    for (int m = 0; m < static_cast<int>(row.size()); ++m) row[m] = 0.25f * (1 + m / (n * n));
    RowTransform(f, n, row);
    for (int m = 0; m < static_cast<int>(row.size()); ++m) {
      const int face = m / (n * n);
      if (m % (n * n) == 0) {
        EXPECT_NEAR(row[m], 0.25f * (1 + face) * n, 1e-5) << m;
      } else {
        ASSERT_NEAR(row[m], 0.0f, 1e-6f) << m;
      }
    }
  }
}

}  // namespace
}  // namespace wavebake
