// The Haar triple product against the pixel domain (Vollick & Lessig §3):
// tripling coefficients (Theorem 7) against Σ_texels b_a b_b b_c of basis
// functions built by inverse-transforming unit vectors, and the tree
// algorithm's W = P(f·g) against the forward transform of the pixel-wise
// product f·g, and ⟨V, W⟩ against Σ_m f_m V_m g_m, on N = 8 cubemaps.
#include "core/products/haar_product.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/products/haar_tree.h"
#include "core/products/tripling.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

constexpr int kN = 8;
constexpr int kPerFace = kN * kN;
constexpr int kM = 6 * kPerFace;

// Basis function `index` of one face as N×N texel values.
std::vector<double> BasisFunction(int index) {
  std::vector<float> img(kPerFace, 0.0f);
  img[index] = 1;
  Inverse2d(WaveletFilter::kHaar, img, kN, kN, MaxDepth(kN, kN));
  return {img.begin(), img.end()};
}

TEST(TriplingCoefficient, MatchesTexelSumsOfBasisFunctions) {
  std::vector<std::vector<double>> basis;
  for (int i = 0; i < kPerFace; ++i) basis.push_back(BasisFunction(i));
  int nonzero = 0;
  for (int a = 0; a < kPerFace; ++a) {
    for (int b = 0; b < kPerFace; ++b) {
      for (int c = 0; c < kPerFace; ++c) {
        double sum = 0;
        for (int m = 0; m < kPerFace; ++m) sum += basis[a][m] * basis[b][m] * basis[c][m];
        const double formula = haar::TriplingCoefficient(kN, a, b, c);
        ASSERT_NEAR(formula, sum, 1e-6) << a << " " << b << " " << c;
        nonzero += formula != 0;
      }
    }
  }
  // Sparse (Ng et al. 2004): far fewer than N⁶ triples.
  EXPECT_LT(nonzero, kPerFace * kPerFace * 3);
  EXPECT_GT(nonzero, kPerFace);
}

// Face-by-face inverse/forward row transform of a scalar or RGB cube.
void ToPixels(std::vector<float>& cube, int channels) {
  std::vector<float> plane(kPerFace);
  for (int face = 0; face < 6; ++face) {
    for (int c = 0; c < channels; ++c) {
      for (int p = 0; p < kPerFace; ++p) plane[p] = cube[(face * kPerFace + p) * channels + c];
      Inverse2d(WaveletFilter::kHaar, plane, kN, kN, MaxDepth(kN, kN));
      for (int p = 0; p < kPerFace; ++p) cube[(face * kPerFace + p) * channels + c] = plane[p];
    }
  }
}
void ToHaar(std::vector<double>& cube, int channels) {
  std::vector<float> plane(kPerFace);
  for (int face = 0; face < 6; ++face) {
    for (int c = 0; c < channels; ++c) {
      for (int p = 0; p < kPerFace; ++p)
        plane[p] = static_cast<float>(cube[(face * kPerFace + p) * channels + c]);
      Forward2d(WaveletFilter::kHaar, plane, kN, kN, MaxDepth(kN, kN));
      for (int p = 0; p < kPerFace; ++p) cube[(face * kPerFace + p) * channels + c] = plane[p];
    }
  }
}

struct Factors {
  std::vector<float> f;  // RGB, Haar
  std::vector<uint32_t> g_index;
  std::vector<float> g_value;
  std::vector<float> g_dense;  // the same g, dense
};

// f with a fraction `f_density` of nonzero coefficients, g with `g_density`;
// g has no term at all on face 5 (a face the product must skip).
Factors RandomFactors(uint32_t seed, double f_density, double g_density) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-1, 1);
  std::uniform_real_distribution<double> keep(0, 1);
  Factors x;
  x.f.assign(3 * kM, 0.0f);
  x.g_dense.assign(kM, 0.0f);
  for (int m = 0; m < kM; ++m) {
    if (keep(rng) < f_density)
      for (int c = 0; c < 3; ++c) x.f[3 * m + c] = value(rng);
    if (m < 5 * kPerFace && keep(rng) < g_density) {
      x.g_dense[m] = value(rng);
      x.g_index.push_back(m);
      x.g_value.push_back(x.g_dense[m]);
    }
  }
  return x;
}

class HaarProductTest : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(HaarProductTest, ProductEqualsForwardTransformOfPixelProduct) {
  const auto [f_density, g_density] = GetParam();
  const Factors x = RandomFactors(17, f_density, g_density);
  const HaarFactor f = HaarFactor::FromDense(kN, x.f);
  HaarProduct kernel(kN);
  RgbCube product(kN);
  kernel.Accumulate(f, x.g_index, x.g_value, product);

  std::vector<float> f_pix = x.f, g_pix = x.g_dense;
  ToPixels(f_pix, 3);
  ToPixels(g_pix, 1);
  std::vector<double> expected(3 * kM);
  for (int m = 0; m < kM; ++m)
    for (int c = 0; c < 3; ++c) expected[3 * m + c] = double{f_pix[3 * m + c]} * g_pix[m];
  ToHaar(expected, 3);
  double err = 0, norm = 0;
  for (int i = 0; i < 3 * kM; ++i) {
    err += std::pow(product.rgb[i] - expected[i], 2);
    norm += expected[i] * expected[i];
  }
  EXPECT_LT(std::sqrt(err / norm), 1e-5);
  EXPECT_FALSE(product.touched[5]);
  for (int i = 3 * 5 * kPerFace; i < 3 * kM; ++i) ASSERT_EQ(product.rgb[i], 0.0f);
}

TEST_P(HaarProductTest, TripleProductEqualsPixelIntegral) {
  const auto [f_density, g_density] = GetParam();
  const Factors x = RandomFactors(29, f_density, g_density);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(0, 1);
  std::vector<float> v(kM);
  for (float& e : v) e = value(rng);  // a dense "visibility" row, Haar domain
  const HaarFactor f = HaarFactor::FromDense(kN, x.f);
  HaarProduct kernel(kN);
  RgbCube product(kN);
  kernel.Accumulate(f, x.g_index, x.g_value, product);

  std::vector<float> f_pix = x.f, g_pix = x.g_dense, v_pix = v;
  ToPixels(f_pix, 3);
  ToPixels(g_pix, 1);
  ToPixels(v_pix, 1);
  for (int c = 0; c < 3; ++c) {
    double tree = 0, pixels = 0, scale = 0;
    for (int m = 0; m < kM; ++m) {
      tree += double{v[m]} * product.rgb[3 * m + c];
      pixels += double{f_pix[3 * m + c]} * v_pix[m] * g_pix[m];
      scale += std::fabs(double{f_pix[3 * m + c]} * v_pix[m] * g_pix[m]);
    }
    EXPECT_LT(std::fabs(tree - pixels), 1e-5 * scale) << "channel " << c;
  }
}

TEST_P(HaarProductTest, ProductMatchesTriplingCoefficientSums) {
  const auto [f_density, g_density] = GetParam();
  const Factors x = RandomFactors(41, f_density, g_density);
  const HaarFactor f = HaarFactor::FromDense(kN, x.f);
  HaarProduct kernel(kN);
  RgbCube product(kN);
  kernel.Accumulate(f, x.g_index, x.g_value, product);
  for (int face = 0; face < 6; ++face) {
    for (int j = 0; j < kPerFace; ++j) {
      double w[3] = {0, 0, 0};
      for (int i = 0; i < kPerFace; ++i) {
        for (int k = 0; k < kPerFace; ++k) {
          const double c = haar::TriplingCoefficient(kN, i, j, k);
          if (c == 0) continue;
          const int fi = face * kPerFace + i, gk = face * kPerFace + k;
          for (int ch = 0; ch < 3; ++ch) w[ch] += c * x.f[3 * fi + ch] * x.g_dense[gk];
        }
      }
      for (int ch = 0; ch < 3; ++ch)
        ASSERT_NEAR(product.rgb[3 * (face * kPerFace + j) + ch], w[ch], 1e-5)
            << "face " << face << " j " << j;
    }
  }
}

// AtTerms reads off the coefficients Accumulate forms, for any wanted set.
TEST_P(HaarProductTest, AtTermsAreTheProductsCoefficients) {
  const auto [f_density, g_density] = GetParam();
  const Factors x = RandomFactors(53, f_density, g_density);
  const HaarFactor f = HaarFactor::FromDense(kN, x.f);
  HaarProduct kernel(kN);
  RgbCube full(kN);
  kernel.Accumulate(f, x.g_index, x.g_value, full);
  std::mt19937 rng(8);
  for (int face = 0; face < 6; ++face) {
    std::vector<uint32_t> g_index;
    std::vector<float> g_value;
    for (size_t k = 0; k < x.g_index.size(); ++k) {
      if (x.g_index[k] / kPerFace != static_cast<uint32_t>(face)) continue;
      g_index.push_back(x.g_index[k]);
      g_value.push_back(x.g_value[k]);
    }
    std::vector<uint32_t> wanted;
    for (int p = 0; p < kPerFace; ++p)
      if (rng() % 3 == 0) wanted.push_back(face * kPerFace + p);
    std::vector<float> got(3 * wanted.size(), -1.0f);
    kernel.AtTerms(f, face, g_index, g_value, wanted, got);
    for (size_t t = 0; t < wanted.size(); ++t)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(got[3 * t + c], full.rgb[3 * wanted[t] + c], 1e-5)
            << "face " << face << " j " << wanted[t];
  }
}

INSTANTIATE_TEST_SUITE_P(Densities, HaarProductTest,
                         ::testing::Values(std::pair{1.0, 1.0}, std::pair{0.2, 0.3},
                                           std::pair{0.05, 0.5}, std::pair{0.5, 0.04}));

TEST(HaarProduct, ClearZeroesWhatAccumulateTouched) {
  const Factors x = RandomFactors(3, 0.5, 0.5);
  const HaarFactor f = HaarFactor::FromDense(kN, x.f);
  HaarProduct kernel(kN);
  RgbCube product(kN);
  kernel.Accumulate(f, x.g_index, x.g_value, product);
  product.Clear();
  for (float v : product.rgb) ASSERT_EQ(v, 0.0f);
  for (int face = 0; face < 6; ++face) EXPECT_FALSE(product.touched[face]);
}

TEST(HaarTree, DecodeInvertsFaceIndex) {
  for (int p = 1; p < kPerFace; ++p) {
    const haar::Position pos = haar::Decode(p % kN, p / kN);
    ASSERT_FALSE(pos.scaling);
    EXPECT_EQ(haar::FaceIndex(kN, pos.level, pos.type, pos.sx, pos.sy), p);
    EXPECT_LT(haar::SquareId(pos.level, pos.sx, pos.sy), haar::SquaresOf(kN));
  }
  EXPECT_TRUE(haar::Decode(0, 0).scaling);
}

}  // namespace
}  // namespace wavebake
