#include "core/wavelets/lifting_rows.h"

#include <cstddef>
#include <cstring>

#include "core/wavelets/thread_scratch.h"

namespace wavebake {
namespace {

// Row r of a bw-wide packed buffer.
float* BufRow(std::span<float> buf, int bw, int r) {
  return buf.data() + static_cast<size_t>(r) * bw;
}

// d_i += c·(s_i + s_{i+1}) with s_h mirrored to s_{h−1}; s rows 0..h−1, d rows h..2h−1.
void PredictRows(std::span<float> buf, int bw, int h, float c) {
  for (int i = 0; i < h; ++i) {
    const float* s0 = BufRow(buf, bw, i);
    const float* s1 = BufRow(buf, bw, i + 1 < h ? i + 1 : i);
    float* d = BufRow(buf, bw, h + i);
    for (int x = 0; x < bw; ++x) d[x] += c * (s0[x] + s1[x]);
  }
}

// s_i += c·(d_{i−1} + d_i) with d_{−1} mirrored to d_0.
void UpdateRows(std::span<float> buf, int bw, int h, float c) {
  for (int i = 0; i < h; ++i) {
    const float* d0 = BufRow(buf, bw, h + (i > 0 ? i - 1 : 0));
    const float* d1 = BufRow(buf, bw, h + i);
    float* s = BufRow(buf, bw, i);
    for (int x = 0; x < bw; ++x) s[x] += c * (d0[x] + d1[x]);
  }
}

void LiftRows(std::span<float> buf, int bw, int h, int k, float c) {
  if (k % 2 == 0) {
    PredictRows(buf, bw, h, c);
  } else {
    UpdateRows(buf, bw, h, c);
  }
}

}  // namespace

void LiftingForwardRows(const LiftingScheme& scheme, std::span<float> img, int width, int bw,
                        int bh) {
  const int h = bh / 2;
  if (h == 0) return;
  std::span<float> buf = ThreadScratch(ScratchSlot::kBlock, static_cast<size_t>(bw) * bh);
  // Even rows become s (rows 0..h−1), odd rows d (rows h..2h−1).
  for (int y = 0; y < bh; ++y) {
    std::memcpy(BufRow(buf, bw, (y % 2) * h + y / 2), img.data() + static_cast<size_t>(y) * width,
                bw * sizeof(float));
  }
  for (int k = 0; k < scheme.count; ++k) LiftRows(buf, bw, h, k, scheme.coeffs[k]);
  for (int r = 0; r < bh; ++r) {
    const float scale = r < h ? scheme.lo_scale : scheme.hi_scale;
    const float* src = BufRow(buf, bw, r);
    float* dst = img.data() + static_cast<size_t>(r) * width;
    for (int x = 0; x < bw; ++x) dst[x] = src[x] * scale;
  }
}

void LiftingInverseRows(const LiftingScheme& scheme, std::span<float> img, int width, int bw,
                        int bh) {
  const int h = bh / 2;
  if (h == 0) return;
  std::span<float> buf = ThreadScratch(ScratchSlot::kBlock, static_cast<size_t>(bw) * bh);
  const float inv_lo = 1 / scheme.lo_scale, inv_hi = 1 / scheme.hi_scale;
  for (int r = 0; r < bh; ++r) {
    const float scale = r < h ? inv_lo : inv_hi;
    const float* src = img.data() + static_cast<size_t>(r) * width;
    float* dst = BufRow(buf, bw, r);
    for (int x = 0; x < bw; ++x) dst[x] = src[x] * scale;
  }
  for (int k = scheme.count - 1; k >= 0; --k) LiftRows(buf, bw, h, k, -scheme.coeffs[k]);
  for (int y = 0; y < bh; ++y) {
    std::memcpy(img.data() + static_cast<size_t>(y) * width, BufRow(buf, bw, (y % 2) * h + y / 2),
                bw * sizeof(float));
  }
}

}  // namespace wavebake
