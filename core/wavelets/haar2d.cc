#include "core/wavelets/haar2d.h"

#include <cstddef>
#include <cstring>

#include "core/bake/bake_params.h"
#include "core/wavelets/separable2d.h"
#include "core/wavelets/thread_scratch.h"

namespace wavebake {

void HaarForwardStep2d(std::span<float> img, int width, int height, int step) {
  const int bw = BlockExtent(width, step), bh = BlockExtent(height, step);
  if (bw < 2 || bh < 2) return SeparableForwardStep(WaveletFilter::kHaar, img, width, height, step);
  const int hw = bw / 2, hh = bh / 2;
  // Outputs of row pair j land in rows j and hh+j, which later pairs still
  // read: build the block in a buffer, then copy it back.
  std::span<float> out = ThreadScratch(ScratchSlot::kBlock, static_cast<size_t>(bw) * bh);
  for (int j = 0; j < hh; ++j) {
    const float* r0 = img.data() + static_cast<size_t>(2 * j) * width;
    const float* r1 = r0 + width;
    float* top = out.data() + static_cast<size_t>(j) * bw;
    float* bottom = out.data() + static_cast<size_t>(hh + j) * bw;
    for (int i = 0; i < hw; ++i) {
      const float a = r0[2 * i], b = r0[2 * i + 1], c = r1[2 * i], d = r1[2 * i + 1];
      top[i] = 0.5f * ((a + b) + (c + d));
      top[hw + i] = 0.5f * ((a - b) + (c - d));
      bottom[i] = 0.5f * ((a + b) - (c + d));
      bottom[hw + i] = 0.5f * ((a - b) - (c - d));
    }
  }
  for (int y = 0; y < bh; ++y) {
    std::memcpy(img.data() + static_cast<size_t>(y) * width,
                out.data() + static_cast<size_t>(y) * bw, bw * sizeof(float));
  }
}

void HaarInverseStep2d(std::span<float> img, int width, int height, int step) {
  const int bw = BlockExtent(width, step), bh = BlockExtent(height, step);
  if (bw < 2 || bh < 2) return SeparableInverseStep(WaveletFilter::kHaar, img, width, height, step);
  const int hw = bw / 2, hh = bh / 2;
  std::span<float> out = ThreadScratch(ScratchSlot::kBlock, static_cast<size_t>(bw) * bh);
  for (int j = 0; j < hh; ++j) {
    const float* top = img.data() + static_cast<size_t>(j) * width;
    const float* bottom = img.data() + static_cast<size_t>(hh + j) * width;
    float* r0 = out.data() + static_cast<size_t>(2 * j) * bw;
    float* r1 = r0 + bw;
    for (int i = 0; i < hw; ++i) {
      const float ll = top[i], hl = top[hw + i], lh = bottom[i], hh_ = bottom[hw + i];
      r0[2 * i] = 0.5f * ((ll + hl) + (lh + hh_));
      r0[2 * i + 1] = 0.5f * ((ll - hl) + (lh - hh_));
      r1[2 * i] = 0.5f * ((ll + hl) - (lh + hh_));
      r1[2 * i + 1] = 0.5f * ((ll - hl) - (lh - hh_));
    }
  }
  for (int y = 0; y < bh; ++y) {
    std::memcpy(img.data() + static_cast<size_t>(y) * width,
                out.data() + static_cast<size_t>(y) * bw, bw * sizeof(float));
  }
}

void HaarForward2d(std::span<float> img, int width, int height, int depth) {
  for (int s = 0; s < depth; ++s) HaarForwardStep2d(img, width, height, s);
}

void HaarInverse2d(std::span<float> img, int width, int height, int depth) {
  for (int s = depth - 1; s >= 0; --s) HaarInverseStep2d(img, width, height, s);
}

}  // namespace wavebake
