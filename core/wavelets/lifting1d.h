#pragma once
// Biorthogonal wavelet steps by lifting (Daubechies & Sweldens factorization)
// with whole-sample symmetric extension, as in JPEG 2000 Part 1 Annex F:
// x[−1] = x[1] and x[n] = x[n−2]. Used for the column filters legall53 and
// cdf97 (DESIGN.md §1 "Column transform"; 4D paper §4.1).
//
// Lifting is invertible step by step whatever the boundary rule, so any even
// length (including 2) reconstructs perfectly.
#include <array>
#include <span>

namespace wavebake {

struct LiftingScheme {
  // Alternating lifting coefficients, starting with a predict step:
  //   predict: d[i] += c·(s[i] + s[i+1])   update: s[i] += c·(d[i−1] + d[i])
  std::array<float, 4> coeffs{};
  int count = 0;
  // Final scaling: lowpass ×lo_scale, highpass ×hi_scale, chosen so that the
  // analysis lowpass DC gain and highpass Nyquist gain are both √2
  // (see core/wavelets/wavelet1d.h).
  float lo_scale = 1, hi_scale = 1;
};

// LeGall 5/3: predict −1/2, update 1/4. Unscaled gains are DC 1 / Nyquist 2,
// so lowpass ×√2 and highpass ×1/√2.
LiftingScheme LeGall53Scheme();
// CDF 9/7 with the JPEG 2000 constants α β γ δ and K = 1.230174104914001.
// Unscaled gains are DC K / Nyquist 2/K, so lowpass ×√2/K and highpass ×K/√2
// (JPEG 2000's own 1/K, K normalization times the orthonormal-like √2 gains).
LiftingScheme Cdf97Scheme();

// line: even length n (or 1: untouched); output [lo | hi]; scratch ≥ n floats.
void LiftingForward1d(const LiftingScheme& scheme, std::span<float> line, std::span<float> scratch);
void LiftingInverse1d(const LiftingScheme& scheme, std::span<float> line, std::span<float> scratch);

}  // namespace wavebake
