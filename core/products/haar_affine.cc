#include "core/products/haar_affine.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace wavebake {
namespace {

// Length of [a0, a1] ∩ [b0, b1].
inline double Overlap(double a0, double a1, double b0, double b1) {
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}

// Below this a coupling is rounding noise of an exact zero (symmetric
// cancellations): the largest coefficient of a level pair is ≥ 2^-12 for
// any supported resolution.
constexpr double kZero = 1e-12;

// 2^e for a small integer e, exactly, without a libm call (the hot loop of
// near-field relighting evaluates these per sample and target level).
inline double ExactPow2(int e) { return std::bit_cast<double>(uint64_t(1023 + e) << 52); }
// 2^(e/2).
inline double SqrtPow2(int e) { return ExactPow2(e >> 1) * ((e & 1) ? M_SQRT2 : 1.0); }

// Fig. 4, with the branch the figure leaves blank (line 7: the transformed
// wavelet lies inside one half of the other, where that one is constant, so
// the integral of a zero-mean wavelet is 0).
inline double PsiPsi(double r, double c) {
  const double d = std::fabs(c - 0.5), sr = r + 0.5, dr = std::fabs(r - 0.5);
  const double maxr = std::max(r, 0.5), minr = std::min(r, 0.5);
  if (d >= sr) return 0;                                            // Fig. 3B: disjoint
  if (d >= maxr) return d - sr;                                     // Fig. 3C
  if (d >= std::max(dr, minr)) return dr - d;                       // Fig. 3D
  if (d >= std::min(dr, minr)) return dr >= minr ? 0 : sr - 3 * d;  // Fig. 3E, 3F
  return 2 * (minr - d);                                            // Fig. 3G
}

// The transformed mother function lives on [c − r, c + r] (split at c), the
// fixed one on [0, 1] (split at ½); each piece is ±1.
inline double Canonical(bool source_wavelet, bool target_wavelet, double r, double c) {
  if (source_wavelet && target_wavelet) return PsiPsi(r, c);
  const double a0 = c - r, a1 = c + r;
  if (source_wavelet) return Overlap(a0, c, 0, 1) - Overlap(c, a1, 0, 1);
  if (target_wavelet) return Overlap(a0, a1, 0, 0.5) - Overlap(a0, a1, 0.5, 1);
  return Overlap(a0, a1, 0, 1);
}

// Eq. 18 for one (source, target level) pair: r, and c + t_k (c of target
// offset t_k is base − t_k); Eq. 16's prefactor 2^{(l_i − l_k)/2}.
struct LevelPair {
  double r, base, prefactor;
};
inline LevelPair Pair(Haar1d source, int target_level, double inv_s, double o) {
  const int dl = target_level - source.level;
  return {ExactPow2(dl - 1) * inv_s,
          (ExactPow2(dl) * (source.offset + 0.5) - ExactPow2(target_level) * o) * inv_s,
          SqrtPow2(-dl)};
}

}  // namespace

int Haar1dCount(int n) { return 2 * (n - 1); }

int Haar1dId(Haar1d f) {
  return 2 * ((1 << f.level) - 1) + (f.wavelet ? (1 << f.level) : 0) + f.offset;
}

Haar1d Haar1dOf(int id) {
  int level = 0;
  while (2 * ((2 << level) - 1) <= id) ++level;
  const int rest = id - 2 * ((1 << level) - 1), width = 1 << level;
  return rest < width ? Haar1d{false, level, rest} : Haar1d{true, level, rest - width};
}

double Haar1dValue(Haar1d f, double v) {
  const double u = std::ldexp(v, f.level) - f.offset;
  if (!(u >= 0 && u < 1)) return 0;
  const double norm = std::sqrt(std::ldexp(1.0, f.level));
  return f.wavelet && u >= 0.5 ? -norm : norm;
}

FactorPair NonStandardFactors(int x, int y) {
  if (x == 0 && y == 0) return {{false, 0, 0}, {false, 0, 0}};
  int level = 0;
  while ((2 << level) <= std::max(x, y)) ++level;
  const int w = 1 << level;
  if (y < w) return {{true, level, x - w}, {false, level, y}};
  if (x < w) return {{false, level, x}, {true, level, y - w}};
  return {{true, level, x - w}, {true, level, y - w}};
}

double CanonicalCoupling(double r, double c) { return PsiPsi(r, c); }

double CanonicalCoupling(bool source_wavelet, bool target_wavelet, double r, double c) {
  return Canonical(source_wavelet, target_wavelet, r, c);
}

double AffineCoupling(Haar1d source, Haar1d target, double s, double o) {
  const LevelPair p = Pair(source, target.level, 1 / s, o);
  return p.prefactor * Canonical(source.wavelet, target.wavelet, p.r, p.base - target.offset);
}

void SourceCouplings(Haar1d source, double s, double o, int n, std::vector<Coupling1d>& out) {
  const double inv_s = 1 / s, width = ExactPow2(-source.level), q0 = source.offset * width;
  const double v0 = (q0 - o) * inv_s, v1 = (q0 + width - o) * inv_s;
  if (!(v1 > 0 && v0 < 1)) return;
  const double vm = (q0 + width / 2 - o) * inv_s;
  const double breakpoints[3] = {v0, source.wavelet ? vm : v0, v1};  // increasing
  const auto emit = [&](bool wavelet, int level, int t, const LevelPair& p) {
    const double d = p.prefactor * Canonical(source.wavelet, wavelet, p.r, p.base - t);
    if (std::fabs(d) > kZero)
      out.push_back({static_cast<uint16_t>(Haar1dId({wavelet, level, t})), static_cast<float>(d)});
  };
  for (int level = 0; (1 << level) < n; ++level) {
    const int count = 1 << level;
    const LevelPair p = Pair(source, level, inv_s, o);
    // Scaling functions: every one that overlaps the image of the support.
    const int first =
        std::clamp(static_cast<int>(std::floor(std::max(v0, 0.0) * count)), 0, count - 1);
    const int last =
        std::clamp(static_cast<int>(std::ceil(std::min(v1, 1.0) * count)) - 1, first, count - 1);
    for (int t = first; t <= last; ++t) emit(false, level, t, p);
    // Wavelets: the ones with a breakpoint inside (at most three, in order).
    int previous = -1;
    for (double bp : breakpoints) {
      if (!(bp > 0 && bp < 1)) continue;
      const int t = std::min(static_cast<int>(bp * count), count - 1);
      if (t == previous) continue;
      previous = t;
      emit(true, level, t, p);
    }
  }
}

}  // namespace wavebake
