#include "core/products/haar_affine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

// ∫ f(v) dv over [a, b] by the midpoint rule; the integrands are piecewise
// constant with a handful of jumps, so the error is ≤ jumps · max|f| · h.
template <typename F>
double Integrate(const F& f, double a, double b, int steps = 100000) {
  const double h = (b - a) / steps;
  double sum = 0;
  for (int i = 0; i < steps; ++i) sum += f(a + (i + 0.5) * h);
  return sum * h;
}

TEST(HaarAffine, FactorIdsNumberEveryFactorOnce) {
  const int n = 32;
  ASSERT_EQ(Haar1dCount(n), 62);
  for (int id = 0; id < Haar1dCount(n); ++id) {
    const Haar1d f = Haar1dOf(id);
    EXPECT_LT(f.level, 5);
    EXPECT_LT(f.offset, 1 << f.level);
    EXPECT_EQ(Haar1dId(f), id);
  }
}

// The factor convention must be the row transform's: the basis vector at
// Mallat position (x, y) (Inverse2d of a unit coefficient) is the product of
// the two continuous factors at the texel centres, / N (the discrete basis
// is orthonormal over N² texels, the continuous one over the unit square).
TEST(HaarAffine, NonStandardFactorsAreTheRowTransformsBasis) {
  const int n = 8;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      std::vector<float> img(n * n, 0.0f);
      img[y * n + x] = 1;
      Inverse2d(WaveletFilter::kHaar, img, n, n, MaxDepth(n, n));
      const FactorPair f = NonStandardFactors(x, y);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const double expected =
              Haar1dValue(f.x, (i + 0.5) / n) * Haar1dValue(f.y, (j + 0.5) / n) / n;
          ASSERT_NEAR(img[j * n + i], expected, 1e-6) << "position " << x << "," << y;
        }
      }
    }
  }
}

TEST(HaarAffine, CanonicalCouplingIsTheIntegralOfTwoMotherFunctions) {
  const auto mother = [](bool wavelet, double u) {
    if (!(u >= 0 && u < 1)) return 0.0;
    return wavelet && u >= 0.5 ? -1.0 : 1.0;
  };
  for (bool sw : {false, true}) {
    for (bool tw : {false, true}) {
      for (double r : {0.05, 0.2, 0.25, 0.4, 0.5, 0.7, 1.0, 2.5}) {
        for (double c = -1.5; c <= 2.5; c += 0.0625 + 0.001) {
          const double numeric = Integrate(
              [&](double u) { return mother(sw, u / (2 * r) - c / (2 * r) + 0.5) * mother(tw, u); },
              0, 1);
          ASSERT_NEAR(CanonicalCoupling(sw, tw, r, c), numeric, 2e-4)
              << "source " << sw << " target " << tw << " r " << r << " c " << c;
        }
      }
    }
  }
}

// §4.2.3: reflection symmetry about c = ½ (Eq. 22) and the r ↔ 1/(4r)
// inversion (Eq. 23); bounds max M = 2 min(r, ½), min M = −min(r, ½).
TEST(HaarAffine, CanonicalCouplingHasThePapersSymmetriesAndBounds) {
  for (double r : {0.1, 0.3, 0.5, 0.8, 1.7}) {
    double lo = 0, hi = 0;
    for (double c = -2; c <= 3; c += 0.01) {
      EXPECT_NEAR(CanonicalCoupling(r, 0.5 + c), CanonicalCoupling(r, 0.5 - c), 1e-12);
      EXPECT_NEAR(CanonicalCoupling(r, c),
                  2 * r * CanonicalCoupling(1 / (4 * r), 0.5 + 1 / (4 * r) - c / (2 * r)), 1e-12);
      lo = std::min(lo, CanonicalCoupling(r, c));
      hi = std::max(hi, CanonicalCoupling(r, c));
    }
    EXPECT_NEAR(hi, 2 * std::min(r, 0.5), 0.03);
    EXPECT_NEAR(lo, -std::min(r, 0.5), 0.03);
  }
}

TEST(HaarAffine, AffineCouplingIsTheIntegralOfScaledTranslatedFunctions) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> id(0, Haar1dCount(16) - 1);
  std::uniform_real_distribution<double> scale(-2.5, 2.5), offset(-1.5, 1.2);
  int nonzero = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Haar1d i = Haar1dOf(id(rng)), k = Haar1dOf(id(rng));
    const double s = std::exp2(scale(rng)), o = offset(rng);
    const double numeric =
        Integrate([&](double v) { return Haar1dValue(i, s * v + o) * Haar1dValue(k, v); }, 0, 1);
    const double d = AffineCoupling(i, k, s, o);
    ASSERT_NEAR(d, numeric, 1e-3 * std::exp2(0.5 * std::abs(i.level - k.level)) + 1e-4)
        << "trial " << trial << " s " << s << " o " << o;
    nonzero += std::fabs(numeric) > 1e-3;
  }
  EXPECT_GT(nonzero, 30);  // the draws reach the interesting (overlapping) cases
}

// The sparse enumeration finds every nonzero coupling and no other.
TEST(HaarAffine, SourceCouplingsAreExactlyTheNonzeroOnes) {
  const int n = 16;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> scale(-3, 3), offset(-2, 1.2);
  for (int trial = 0; trial < 40; ++trial) {
    const double s = std::exp2(scale(rng)), o = offset(rng);
    for (int i = 0; i < Haar1dCount(n); ++i) {
      std::vector<Coupling1d> sparse;
      SourceCouplings(Haar1dOf(i), s, o, n, sparse);
      std::map<int, float> found;
      for (const Coupling1d& c : sparse) EXPECT_TRUE(found.emplace(c.target, c.value).second);
      for (int k = 0; k < Haar1dCount(n); ++k) {
        const double d = AffineCoupling(Haar1dOf(i), Haar1dOf(k), s, o);
        if (std::fabs(d) > 1e-9) {
          ASSERT_TRUE(found.count(k)) << "missed target " << k << " of source " << i;
          EXPECT_NEAR(found[k], d, 1e-6);
        } else {
          EXPECT_FALSE(found.count(k) && std::fabs(found[k]) > 1e-9);
        }
      }
    }
  }
}

// Appendix D: a target at level l_k overlaps at most s·2^{l_i − l_k} + 1
// sources of one kind at level l_i, and a source at most 2^{l_k − l_i}/s + 1
// targets, so a whole tree has at most min(Σ (s 2^{l_i} + 2^{l_k}),
// Σ (2^{l_k}/s + 2^{l_i})) overlapping pairs — ×4 here, for the two kinds
// (φ, ψ) on either side: O(N log N).
TEST(HaarAffine, CouplingsOfAWholeTreeMeetAppendixDsBound) {
  for (int n : {16, 64}) {
    for (double s : {0.3, 1.0, 3.0}) {
      size_t total = 0;
      for (int i = 0; i < Haar1dCount(n); ++i) {
        std::vector<Coupling1d> sparse;
        SourceCouplings(Haar1dOf(i), s, 0.1, n, sparse);
        total += sparse.size();
      }
      double by_target = 0, by_source = 0;
      for (int li = 0; (1 << li) < n; ++li) {
        for (int lk = 0; (1 << lk) < n; ++lk) {
          by_target += s * std::exp2(li) + std::exp2(lk);
          by_source += std::exp2(lk) / s + std::exp2(li);
        }
      }
      EXPECT_LE(total, 4 * std::min(by_target, by_source)) << "n " << n << " s " << s;
      EXPECT_GT(total, static_cast<size_t>(Haar1dCount(n)) / 2);  // and it is not empty
    }
  }
}

}  // namespace
}  // namespace wavebake
