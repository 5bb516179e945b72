#include "core/wavelets/wavelet2d.h"

#include <algorithm>
#include <bit>

#include "core/wavelets/haar2d.h"
#include "core/wavelets/separable2d.h"

namespace wavebake {

int MaxDepth(int width, int height) {
  const int m = std::max(1, std::min(width, height));
  return std::bit_width(static_cast<unsigned>(m)) - 1;
}

void ForwardStep(WaveletFilter f, std::span<float> img, int width, int height, int step) {
  if (f == WaveletFilter::kHaar) return HaarForwardStep2d(img, width, height, step);
  SeparableForwardStep(f, img, width, height, step);
}

void InverseStep(WaveletFilter f, std::span<float> img, int width, int height, int step) {
  if (f == WaveletFilter::kHaar) return HaarInverseStep2d(img, width, height, step);
  SeparableInverseStep(f, img, width, height, step);
}

void Forward2d(WaveletFilter f, std::span<float> img, int width, int height, int depth) {
  for (int s = 0; s < depth; ++s) ForwardStep(f, img, width, height, s);
}

void Inverse2d(WaveletFilter f, std::span<float> img, int width, int height, int depth) {
  for (int s = depth - 1; s >= 0; --s) InverseStep(f, img, width, height, s);
}

}  // namespace wavebake
