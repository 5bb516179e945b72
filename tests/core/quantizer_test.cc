// Quantizer (DESIGN.md §1 "Scaling and quantization"): error bound for every
// bit depth, the statistics subtractive dither must have, and a dither stream
// reproducible from its documented formula.
#include "core/columns/quantizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace wavebake {
namespace {

struct Column {
  std::vector<float> values;
  std::vector<uint32_t> positions;
  std::vector<uint8_t> levels;
};

// Wavelet-like column: coefficient at level l ~ 2^−l (4D paper §4.3).
Column RandomColumn(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0, 1);
  std::uniform_int_distribution<int> lvl(0, 9);
  Column c;
  for (int i = 0; i < n; ++i) {
    const int l = lvl(rng);
    c.levels.push_back(static_cast<uint8_t>(l));
    c.values.push_back(std::ldexp(g(rng), -l));
    c.positions.push_back(static_cast<uint32_t>(7 * i + 3));
  }
  return c;
}

struct Coded {
  std::vector<int16_t> q;
  float step = 0;
};

// The paper's rule with b bits: the column's largest |v/k| gets code Q_b.
std::vector<float> RoundTrip(const Column& c, LevelScaling s, int bits, uint64_t seed,
                             uint64_t column, Coded* out = nullptr) {
  const int qmax = MaxQuantCode(bits);
  Coded coded;
  coded.step = StepForMax(LevelScaledMax(c.values, c.levels, s), qmax);
  coded.q = Quantize(c.values, c.positions, c.levels, s, coded.step, qmax, seed, column);
  std::vector<float> v(c.values.size());
  Dequantize(coded.q, c.positions, c.levels, s, coded.step, seed, column, v);
  if (out) *out = coded;
  return v;
}

TEST(QuantizerTest, ErrorWithinBoundForAllBitDepthsAndScalings) {
  const Column c = RandomColumn(2000, 1);
  for (LevelScaling s : {LevelScaling::kPaper, LevelScaling::kUniform}) {
    for (int bits = 2; bits <= 16; ++bits) {
      Coded qc;
      const std::vector<float> out = RoundTrip(c, s, bits, 42, 7, &qc);
      const int qmax = MaxQuantCode(bits);
      double worst_ratio = 0;
      for (size_t i = 0; i < out.size(); ++i) {
        ASSERT_LE(std::abs(qc.q[i]), qmax);
        const double err = std::fabs(double(out[i]) - c.values[i]);
        ASSERT_LE(err, QuantizationBound(qc.step, c.levels[i], s, qmax)) << bits << " " << i;
        // Half a step, independently: Δ/2 · 2^−l (paper) or Δ/2 (uniform).
        const double k = s == LevelScaling::kPaper ? std::ldexp(1.0, -c.levels[i]) : 1.0;
        worst_ratio = std::max(worst_ratio, err / (qc.step * k / 2));
      }
      // Dither spreads errors over the whole half step: the bound is nearly met.
      EXPECT_GT(worst_ratio, 0.9) << "bits " << bits;
    }
  }
}

TEST(QuantizerTest, StepReachesTheLargestLevelScaledMagnitude) {
  const Column c = RandomColumn(300, 2);
  double paper = 0, uniform = 0;
  for (size_t i = 0; i < c.values.size(); ++i) {
    paper = std::max(paper, std::fabs(std::ldexp(double(c.values[i]), c.levels[i])));
    uniform = std::max(uniform, std::fabs(double(c.values[i])));
  }
  EXPECT_EQ(LevelScaledMax(c.values, c.levels, LevelScaling::kPaper), paper);
  EXPECT_EQ(LevelScaledMax(c.values, c.levels, LevelScaling::kUniform), uniform);
  const float step = StepForMax(paper, 255);
  EXPECT_GE(double(step) * 255, paper);
  EXPECT_LT(double(std::nextafter(step, 0.0f)) * 255, paper);  // the smallest such float
}

TEST(QuantizerTest, SubtractiveDitherErrorIsUniformAndUnbiased) {
  // A constant input sits at the same spot between two levels for every
  // coefficient; without dither every error would be equal. With subtractive
  // dither the error is uniform on ±½ step: mean 0, variance step²/12.
  const int n = 20000;
  const float step = 1.0f / 31;
  Column c;
  for (int i = 0; i < n; ++i) {
    c.values.push_back(0.3137f);
    c.positions.push_back(static_cast<uint32_t>(i));
    c.levels.push_back(3);  // uniform: the level does not change the step
  }
  const auto s = LevelScaling::kUniform;
  const std::vector<int16_t> q = Quantize(c.values, c.positions, c.levels, s, step, 31, 5, 11);
  std::vector<float> out(n);
  Dequantize(q, c.positions, c.levels, s, step, 5, 11, out);
  double mean = 0, var = 0;
  for (int i = 0; i < n; ++i) mean += (out[i] - c.values[i]) / step;
  mean /= n;
  for (int i = 0; i < n; ++i) var += std::pow((out[i] - c.values[i]) / step - mean, 2);
  var /= n - 1;
  EXPECT_NEAR(mean, 0.0, 0.01);       // σ/√n ≈ 0.002
  EXPECT_NEAR(var, 1.0 / 12, 0.004);  // 1/12 ≈ 0.0833
}

TEST(QuantizerTest, ZeroStepDecodesToZero) {
  Column zero{{0, 0, 0}, {1, 2, 3}, {0, 2, 5}};
  Coded qc;
  const std::vector<float> out = RoundTrip(zero, LevelScaling::kPaper, 8, 1, 2, &qc);
  EXPECT_EQ(qc.step, 0.0f);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(qc.q[i], 0);
    EXPECT_EQ(out[i], 0.0f);
  }
  EXPECT_TRUE(Quantize({}, {}, {}, LevelScaling::kUniform, 1.0f, 127, 1, 2).empty());
}

TEST(QuantizerTest, ExtremesMapToFullScaleCodes) {
  // ±max has y = ±Q: Q + u ∈ [Q − ½, Q + ½) rounds (half away from zero) to
  // Q, and −Q + u ∈ [−Q − ½, −Q + ½) to −Q (−Q − 1 at u = −½ is clamped).
  Column c{{1.0f, -0.5f, 0.25f}, {0, 1, 2}, {0, 1, 2}};  // all ±1 after 2^l (paper)
  for (int bits = 2; bits <= 16; ++bits) {
    const int qmax = MaxQuantCode(bits);
    Coded qc;
    RoundTrip(c, LevelScaling::kPaper, bits, 3, 4, &qc);
    EXPECT_EQ(qc.q[0], qmax);
    EXPECT_EQ(qc.q[1], -qmax);
    EXPECT_EQ(qc.q[2], qmax);
  }
}

TEST(QuantizerTest, CodesAreClampedToTheLargestCode) {
  // A step too fine for int16 must not wrap: codes saturate at ±max_code.
  Column c{{1.0f, -1.0f}, {0, 1}, {0, 0}};
  const auto q = Quantize(c.values, c.positions, c.levels, LevelScaling::kUniform, 1e-6f,
                          kMaxStoredCode, 1, 1);
  EXPECT_EQ(q[0], kMaxStoredCode);
  EXPECT_EQ(q[1], -kMaxStoredCode);
  EXPECT_EQ(BitsForCode(kMaxStoredCode), 16);
  EXPECT_EQ(BitsForCode(1), 2);
  EXPECT_EQ(BitsForCode(4), 4);  // 100b plus sign
}

// The header's formula, q = clamp(round(v/Δ + u), −C, C) with std::round
// (half away from zero), written out with libm. With Δ = 1, v = ±½ − u is a
// float (u has 24 bits below ½) and v + u lands on ±½ exactly: those round
// to ±1. Random values of either sign agree with the formula too.
TEST(QuantizerTest, RoundsHalfAwayFromZeroAsTheFormulaSays) {
  constexpr uint64_t kSeed = 5, kColumn = 9;
  Column halves, random = RandomColumn(4000, 8);
  for (uint32_t p = 0; p < 1000; ++p) {
    const double u = DitherAt(kSeed, kColumn, p);
    for (double h : {0.5, -0.5}) {
      halves.values.push_back(static_cast<float>(h - u));
      ASSERT_EQ(double{halves.values.back()} + u, h);
      halves.positions.push_back(p);
      halves.levels.push_back(0);
    }
  }
  const std::vector<int16_t> q =
      Quantize(halves.values, halves.positions, halves.levels, LevelScaling::kUniform, 1.0f,
               kMaxStoredCode, kSeed, kColumn);
  for (size_t i = 0; i < q.size(); ++i) EXPECT_EQ(q[i], i % 2 == 0 ? 1 : -1) << i;

  const float step = 0.01f;
  const int c = 100;  // some values beyond ±C·Δ, clamped
  const std::vector<int16_t> r = Quantize(random.values, random.positions, random.levels,
                                          LevelScaling::kUniform, step, c, kSeed, kColumn);
  for (size_t i = 0; i < r.size(); ++i) {
    const double u = DitherAt(kSeed, kColumn, random.positions[i]);
    const double y = std::round(double{random.values[i]} / double{step} + u);
    EXPECT_EQ(r[i], std::clamp(y, double(-c), double(c))) << i;
  }
}

TEST(QuantizerTest, DeterministicForSeedAndColumn) {
  const Column c = RandomColumn(500, 3);
  const auto s = LevelScaling::kPaper;
  Coded a, b, other;
  RoundTrip(c, s, 10, 99, 5, &a);
  RoundTrip(c, s, 10, 99, 5, &b);
  EXPECT_EQ(a.q, b.q);
  RoundTrip(c, s, 10, 100, 5, &other);
  EXPECT_NE(a.q, other.q);
}

// The documented formula (core/columns/quantizer.h), written out independently.
uint64_t SplitMix(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

TEST(DitherTest, MatchesDocumentedSplitMixFormula) {
  // Anchor: splitmix64 seeded with 0 first yields 0xE220A8397B1DCDAF.
  ASSERT_EQ(SplitMix(0), 0xE220A8397B1DCDAFull);
  for (const uint64_t seed : {0ull, 1ull, 0xDEADBEEFull}) {
    for (const uint64_t column : {0ull, 5ull, 123456ull}) {
      for (const uint32_t pos : {0u, 1u, 65535u}) {
        const uint64_t h = SplitMix(SplitMix(SplitMix(seed) ^ column) ^ pos);
        const double u = double(h >> 40) / 16777216.0 - 0.5;
        EXPECT_EQ(DitherAt(seed, column, pos), static_cast<float>(u));
      }
    }
  }
}

TEST(DitherTest, UniformOnHalfOpenInterval) {
  const int n = 100000;
  double mean = 0, var = 0, lo = 1, hi = -1;
  for (int i = 0; i < n; ++i) {
    const double u = DitherAt(7, 3, static_cast<uint32_t>(i));
    ASSERT_GE(u, -0.5);
    ASSERT_LT(u, 0.5);
    lo = std::min(lo, u), hi = std::max(hi, u);
    mean += u;
    var += u * u;
  }
  mean /= n;
  var = var / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 0.005);
  EXPECT_NEAR(var, 1.0 / 12, 0.002);
  EXPECT_LT(lo, -0.499);
  EXPECT_GT(hi, 0.499);
}

TEST(DitherTest, ColumnsAndSeedsGiveDifferentStreams) {
  int same_column = 0, same_seed = 0;
  for (uint32_t i = 0; i < 1000; ++i) {
    same_column += DitherAt(1, 2, i) == DitherAt(1, 3, i);
    same_seed += DitherAt(1, 2, i) == DitherAt(2, 2, i);
  }
  EXPECT_LT(same_column, 5);
  EXPECT_LT(same_seed, 5);
}

}  // namespace
}  // namespace wavebake
