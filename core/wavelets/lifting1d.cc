#include "core/wavelets/lifting1d.h"

#include <cmath>
#include <cstring>

namespace wavebake {
namespace {

// d[i] += c·(s[i] + s[i+1]); the right neighbour of the last odd sample is
// x[n] = x[n−2], i.e. s[h] mirrors to s[h−1].
void Predict(std::span<const float> s, std::span<float> d, float c) {
  const size_t h = s.size();
  for (size_t i = 0; i + 1 < h; ++i) d[i] += c * (s[i] + s[i + 1]);
  d[h - 1] += c * (2 * s[h - 1]);
}

// s[i] += c·(d[i−1] + d[i]); the left neighbour of x[0] is x[−1] = x[1],
// i.e. d[−1] mirrors to d[0].
void Update(std::span<float> s, std::span<const float> d, float c) {
  const size_t h = s.size();
  s[0] += c * (2 * d[0]);
  for (size_t i = 1; i < h; ++i) s[i] += c * (d[i - 1] + d[i]);
}

// Step k of a scheme: even k predict, odd k update.
void Lift(std::span<float> s, std::span<float> d, int k, float c) {
  if (k % 2 == 0) {
    Predict(s, d, c);
  } else {
    Update(s, d, c);
  }
}

}  // namespace

LiftingScheme LeGall53Scheme() {
  const float r2 = static_cast<float>(M_SQRT2);
  return {{-0.5f, 0.25f, 0, 0}, 2, r2, 1 / r2};
}

LiftingScheme Cdf97Scheme() {
  constexpr double kAlpha = -1.586134342059924, kBeta = -0.052980118572961;
  constexpr double kGamma = 0.882911075530934, kDelta = 0.443506852043971;
  constexpr double kK = 1.230174104914001;
  return {{float(kAlpha), float(kBeta), float(kGamma), float(kDelta)},
          4,
          float(M_SQRT2 / kK),
          float(kK / M_SQRT2)};
}

void LiftingForward1d(const LiftingScheme& scheme, std::span<float> line,
                      std::span<float> scratch) {
  const size_t h = line.size() / 2;
  if (h == 0) return;
  std::span<float> s = scratch.first(h), d = scratch.subspan(h, h);
  for (size_t i = 0; i < h; ++i) {
    s[i] = line[2 * i];
    d[i] = line[2 * i + 1];
  }
  for (int k = 0; k < scheme.count; ++k) Lift(s, d, k, scheme.coeffs[k]);
  for (size_t i = 0; i < h; ++i) {
    line[i] = s[i] * scheme.lo_scale;
    line[h + i] = d[i] * scheme.hi_scale;
  }
}

void LiftingInverse1d(const LiftingScheme& scheme, std::span<float> line,
                      std::span<float> scratch) {
  const size_t h = line.size() / 2;
  if (h == 0) return;
  std::span<float> s = scratch.first(h), d = scratch.subspan(h, h);
  const float inv_lo = 1 / scheme.lo_scale, inv_hi = 1 / scheme.hi_scale;
  for (size_t i = 0; i < h; ++i) {
    s[i] = line[i] * inv_lo;
    d[i] = line[h + i] * inv_hi;
  }
  for (int k = scheme.count - 1; k >= 0; --k) Lift(s, d, k, -scheme.coeffs[k]);
  for (size_t i = 0; i < h; ++i) {
    line[2 * i] = s[i];
    line[2 * i + 1] = d[i];
  }
}

}  // namespace wavebake
