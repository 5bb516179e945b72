#include "core/wavelets/daub4_1d.h"

#include <cmath>
#include <cstddef>
#include <cstring>

#include "core/wavelets/thread_scratch.h"

namespace wavebake {
namespace {

// Daubechies (1988) 4-tap scaling filter h_k = (1+√3, 3+√3, 3−√3, 1−√3)/(4√2);
// the wavelet filter is its quadrature mirror g_k = (−1)^k h_{3−k}.
struct Daub4Taps {
  float h[4];
  float g[4];
};

constexpr Daub4Taps MakeTaps() {
  constexpr double s3 = 1.7320508075688772935, d = 4 * 1.4142135623730950488;
  constexpr double h0 = (1 + s3) / d, h1 = (3 + s3) / d, h2 = (3 - s3) / d, h3 = (1 - s3) / d;
  return {{float(h0), float(h1), float(h2), float(h3)},
          {float(h3), float(-h2), float(h1), float(-h0)}};
}
constexpr Daub4Taps kTaps = MakeTaps();

}  // namespace

// lo[i] = Σ_k h_k x[(2i+k) mod n], hi[i] = Σ_k g_k x[(2i+k) mod n].
void Daub4Forward1d(std::span<float> line, std::span<float> scratch) {
  const size_t n = line.size(), h = n / 2;
  if (h == 0) return;
  const auto& [hk, gk] = kTaps;
  for (size_t i = 0; i < h; ++i) {
    // Only the last pair wraps (to x[0], x[1]); no modulo in the hot loop.
    const size_t j = i + 1 < h ? 2 * i + 2 : 0;
    const float x0 = line[2 * i], x1 = line[2 * i + 1], x2 = line[j], x3 = line[j + 1];
    scratch[i] = hk[0] * x0 + hk[1] * x1 + hk[2] * x2 + hk[3] * x3;
    scratch[h + i] = gk[0] * x0 + gk[1] * x1 + gk[2] * x2 + gk[3] * x3;
  }
  std::memcpy(line.data(), scratch.data(), n * sizeof(float));
}

// The transpose of the forward matrix: x[2m] collects taps 0 and 2 (from pairs
// m and m−1 mod h), x[2m+1] taps 1 and 3. For n = 2 both pairs are the same
// one and the taps add up, exactly as the forward wrap did.
void Daub4Inverse1d(std::span<float> line, std::span<float> scratch) {
  const size_t n = line.size(), h = n / 2;
  if (h == 0) return;
  const auto& [hk, gk] = kTaps;
  for (size_t m = 0; m < h; ++m) {
    const size_t p = m > 0 ? m - 1 : h - 1;
    const float lo = line[m], hi = line[h + m], lo_p = line[p], hi_p = line[h + p];
    scratch[2 * m] = hk[0] * lo + gk[0] * hi + hk[2] * lo_p + gk[2] * hi_p;
    scratch[2 * m + 1] = hk[1] * lo + gk[1] * hi + hk[3] * lo_p + gk[3] * hi_p;
  }
  std::memcpy(line.data(), scratch.data(), n * sizeof(float));
}

namespace {

float* Row(std::span<float> img, int width, int r) {
  return img.data() + static_cast<size_t>(r) * width;
}

// out = a·p + b·q + c·r + d·s over bw floats.
void Combine4(float* out, float a, const float* p, float b, const float* q, float c, const float* r,
              float d, const float* s, int bw) {
  for (int x = 0; x < bw; ++x) out[x] = a * p[x] + b * q[x] + c * r[x] + d * s[x];
}

}  // namespace

void Daub4ForwardRows(std::span<float> img, int width, int bw, int bh) {
  const int h = bh / 2;
  if (h == 0) return;
  std::span<float> buf = ThreadScratch(ScratchSlot::kBlock, static_cast<size_t>(bw) * bh);
  const auto& [hk, gk] = kTaps;
  for (int i = 0; i < h; ++i) {
    const int j = i + 1 < h ? 2 * i + 2 : 0;
    const float *x0 = Row(img, width, 2 * i), *x1 = Row(img, width, 2 * i + 1);
    const float *x2 = Row(img, width, j), *x3 = Row(img, width, j + 1);
    Combine4(Row(buf, bw, i), hk[0], x0, hk[1], x1, hk[2], x2, hk[3], x3, bw);
    Combine4(Row(buf, bw, h + i), gk[0], x0, gk[1], x1, gk[2], x2, gk[3], x3, bw);
  }
  for (int r = 0; r < bh; ++r) std::memcpy(Row(img, width, r), Row(buf, bw, r), bw * sizeof(float));
}

void Daub4InverseRows(std::span<float> img, int width, int bw, int bh) {
  const int h = bh / 2;
  if (h == 0) return;
  std::span<float> buf = ThreadScratch(ScratchSlot::kBlock, static_cast<size_t>(bw) * bh);
  const auto& [hk, gk] = kTaps;
  for (int m = 0; m < h; ++m) {
    const int p = m > 0 ? m - 1 : h - 1;
    const float *lo = Row(img, width, m), *hi = Row(img, width, h + m);
    const float *lo_p = Row(img, width, p), *hi_p = Row(img, width, h + p);
    Combine4(Row(buf, bw, 2 * m), hk[0], lo, gk[0], hi, hk[2], lo_p, gk[2], hi_p, bw);
    Combine4(Row(buf, bw, 2 * m + 1), hk[1], lo, gk[1], hi, hk[3], lo_p, gk[3], hi_p, bw);
  }
  for (int r = 0; r < bh; ++r) std::memcpy(Row(img, width, r), Row(buf, bw, r), bw * sizeof(float));
}

}  // namespace wavebake
