#pragma once
// The microfacet pieces of the `ggx` BRDF (core/products/brdf.h): the Trowbridge–Reitz
// (GGX) normal distribution and its Smith shadowing (Walter et al. 2007;
// Heitz 2014, "Understanding the masking-shadowing function"), in terms of
// cosines to the macro normal. Exposed so tests can check them against their
// own identities: ∫ D(h)(n·h) dω_h = 1 and the weak white furnace
// ∫ D(h) G₁(ω_o) / (4 n·ω_o) dω_i = 1.
#include <algorithm>
#include <cmath>
#include <numbers>

namespace wavebake::ggx {

// D(h) for cos θ_h = n·h (0 for n·h ≤ 0).
inline double D(double alpha, double cos_h) {
  if (cos_h <= 0) return 0;
  const double a2 = alpha * alpha, c2 = cos_h * cos_h;
  const double d = c2 * (a2 - 1) + 1;
  return a2 / (std::numbers::pi * d * d);
}

// Smith Λ(ω) for cos θ = n·ω > 0.
inline double Lambda(double alpha, double cos_w) {
  const double c2 = std::clamp(cos_w * cos_w, 1e-12, 1.0);
  const double tan2 = (1 - c2) / c2;
  return 0.5 * (std::sqrt(1 + alpha * alpha * tan2) - 1);
}

inline double G1(double alpha, double cos_w) { return 1 / (1 + Lambda(alpha, cos_w)); }
// Height-correlated masking-shadowing.
inline double G2(double alpha, double cos_i, double cos_o) {
  return 1 / (1 + Lambda(alpha, cos_i) + Lambda(alpha, cos_o));
}

}  // namespace wavebake::ggx
