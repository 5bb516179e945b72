// Subband bookkeeping: SubbandAt against counts and against where the
// transform actually puts each kind of basis function; synthesis norms
// against independent impulse inverses; RowLevel against the Haar layout.
#include "core/wavelets/subband.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <thread>
#include <utility>
#include <vector>

#include "core/wavelets/wavelet2d.h"
#include "tests/core/wavelet_test_util.h"

namespace wavebake {
namespace {

std::map<std::pair<int, int>, int> CountSubbands(int w, int h, int depth) {
  std::map<std::pair<int, int>, int> counts;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Subband sb = SubbandAt(x, y, w, h, depth);
      ++counts[{sb.level, sb.band}];
    }
  }
  return counts;
}

TEST(SubbandTest, SquareFullDepthHasFourToTheLevelPerDetailBand) {
  const int n = 32, d = MaxDepth(n, n);
  const auto counts = CountSubbands(n, n, d);
  EXPECT_EQ(counts.size(), 1u + 3u * d);
  EXPECT_EQ(counts.at({0, 0}), 1);
  for (int l = 0; l < d; ++l) {
    for (int b = 1; b <= 3; ++b) EXPECT_EQ(counts.at({l, b}), 1 << (2 * l)) << l << "," << b;
  }
}

TEST(SubbandTest, NonSquarePartialDepthCounts) {
  // 32×8 at depth 2: LL is 8×2; step s details are (32>>(s+1))×(8>>(s+1)).
  const auto counts = CountSubbands(32, 8, 2);
  EXPECT_EQ(counts.size(), 7u);
  EXPECT_EQ(counts.at({0, 0}), 8 * 2);
  for (int b = 1; b <= 3; ++b) {
    EXPECT_EQ(counts.at({0, b}), 8 * 2);   // step 1
    EXPECT_EQ(counts.at({1, b}), 16 * 4);  // step 0
  }
}

TEST(SubbandTest, DepthZeroIsAllPixelBasis) {
  const auto counts = CountSubbands(8, 4, 0);
  ASSERT_EQ(counts.size(), 1u);
  EXPECT_EQ(counts.at({0, 0}), 32);
}

TEST(SubbandTest, AgreesWithHaarBasisFunctionShape) {
  // Inverse Haar of an impulse is the basis function itself: its support side
  // is 2^(d−level) for details (2^d for LL) and its sign flips along x for
  // band 1, along y for band 2, both for band 3.
  const int w = 16, h = 8, d = 3;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::vector<float> img(w * h, 0.0f);
      img[y * w + x] = 1;
      Inverse2d(WaveletFilter::kHaar, img, w, h, d);
      int x0 = w, x1 = -1, y0 = h, y1 = -1;
      for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
          if (img[j * w + i] == 0) continue;
          x0 = std::min(x0, i), x1 = std::max(x1, i), y0 = std::min(y0, j), y1 = std::max(y1, j);
        }
      }
      const Subband sb = SubbandAt(x, y, w, h, d);
      const int side = sb.band == 0 ? 1 << d : 1 << (d - sb.level);
      ASSERT_EQ(x1 - x0 + 1, side) << x << "," << y;
      ASSERT_EQ(y1 - y0 + 1, side) << x << "," << y;
      const float tl = img[y0 * w + x0], tr = img[y0 * w + x1], bl = img[y1 * w + x0];
      EXPECT_EQ(tr == -tl, (sb.band & 1) != 0) << x << "," << y;
      EXPECT_EQ(bl == -tl, (sb.band & 2) != 0) << x << "," << y;
    }
  }
}

TEST(SubbandTest, RowLevelCountsAndAgreesWithFullDepthSubbands) {
  const int n = 32, d = MaxDepth(n, n);
  std::map<int, int> counts;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int rl = RowLevel(x, y);
      ++counts[rl];
      // RowLevel counts the scaling coefficient as its own level 0, so the
      // coarsest details are row level 1.
      const Subband sb = SubbandAt(x, y, n, n, d);
      EXPECT_EQ(rl, sb.band == 0 ? 0 : sb.level + 1) << x << "," << y;
    }
  }
  EXPECT_EQ(counts[0], 1);
  for (int l = 1; l <= d; ++l) EXPECT_EQ(counts[l], 3 << (2 * (l - 1))) << l;
}

TEST(SynthesisNormsTest, OrthonormalFiltersGiveExactlyOne) {
  for (const WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kDaub4}) {
    for (const int d : {0, 2, 5}) {
      for (const float v : SynthesisNorms(f, 32, 32, d)) ASSERT_EQ(v, 1.0f);
    }
  }
}

double ImpulseNorm(WaveletFilter f, int x, int y, int w, int h, int d) {
  std::vector<float> img(w * h, 0.0f);
  img[y * w + x] = 1;
  Inverse2d(f, img, w, h, d);
  return std::sqrt(testing::Dot(img, img));
}

TEST(SynthesisNormsTest, BiorthogonalNormsMatchImpulsesAtOtherInteriorCoefficients) {
  // The per-subband weight is measured at the subband's centre; any other
  // coefficient well inside the subband must have the same norm.
  // 256×256 at depth 3: every subband is ≥ 32 wide and these points sit ≥ 60
  // pixels from the border, beyond the ±25 pixel support of a 9/7 basis.
  const int w = 256, h = 256, d = 3;
  for (const WaveletFilter f : {WaveletFilter::kLeGall53, WaveletFilter::kCdf97}) {
    const std::vector<float>& norms = SynthesisNormsRef(f, w, h, d);
    for (const auto& [x, y] : {std::pair{10, 12}, std::pair{20, 25}, std::pair{45, 10},
                               std::pair{10, 50}, std::pair{50, 50}, std::pair{100, 20},
                               std::pair{30, 100}, std::pair{200, 60}, std::pair{180, 220}}) {
      EXPECT_NEAR(norms[y * w + x], ImpulseNorm(f, x, y, w, h, d), 1e-4)
          << testing::FilterName(f) << " at " << x << "," << y;
    }
  }
}

TEST(SynthesisNormsTest, BiorthogonalNormsAreCloseToOneInTheInterior) {
  // Documented tolerance (core/wavelets/subband.h): subbands at least 8 wide, i.e. the
  // basis function is not folded by the symmetric extension.
  const int n = 128;
  for (int d = 1; d <= 4; ++d) {
    for (const auto& [f, lo, hi] : {std::tuple{WaveletFilter::kLeGall53, 0.66, 1.44},
                                    std::tuple{WaveletFilter::kCdf97, 0.96, 1.08}}) {
      const std::vector<float> norms = SynthesisNorms(f, n, n, d);
      for (const float v : norms) {
        ASSERT_GE(v, lo) << testing::FilterName(f) << " d=" << d;
        ASSERT_LE(v, hi) << testing::FilterName(f) << " d=" << d;
      }
    }
  }
  // LeGall 5/3 first-level values from its filters: lowpass synthesis taps
  // (½, 1, ½)/√2 have norm² ¾; highpass (−⅛, −¼, ¾, −¼, −⅛)·√2 has norm² 23/16.
  const std::vector<float>& n1 = SynthesisNormsRef(WaveletFilter::kLeGall53, 64, 64, 1);
  EXPECT_NEAR(n1[16 * 64 + 16], 0.75, 1e-6);                         // LL: ¾
  EXPECT_NEAR(n1[16 * 64 + 48], std::sqrt(0.75 * 23 / 16.0), 1e-6);  // HL
  EXPECT_NEAR(n1[48 * 64 + 48], 23 / 16.0, 1e-6);                    // HH
}

TEST(SynthesisNormsTest, CacheIsSharedAcrossThreads) {
  std::vector<const std::vector<float>*> seen(4, nullptr);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back(
        [&seen, t] { seen[t] = &SynthesisNormsRef(WaveletFilter::kCdf97, 64, 32, 2); });
  }
  for (auto& th : threads) th.join();
  for (int t = 1; t < 4; ++t) EXPECT_EQ(seen[t], seen[0]);
  EXPECT_EQ(seen[0]->size(), 64u * 32u);
}

}  // namespace
}  // namespace wavebake
