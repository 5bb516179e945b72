#include "core/wavelets/wavelet1d.h"

#include <cmath>
#include <cstring>

#include "core/wavelets/daub4_1d.h"
#include "core/wavelets/lifting1d.h"

namespace wavebake {

void HaarForward1d(std::span<float> line, std::span<float> scratch) {
  const size_t h = line.size() / 2;
  if (h == 0) return;
  const float r = static_cast<float>(M_SQRT1_2);
  for (size_t i = 0; i < h; ++i) {
    const float a = line[2 * i], b = line[2 * i + 1];
    scratch[i] = (a + b) * r;
    scratch[h + i] = (a - b) * r;
  }
  std::memcpy(line.data(), scratch.data(), 2 * h * sizeof(float));
}

void HaarInverse1d(std::span<float> line, std::span<float> scratch) {
  const size_t h = line.size() / 2;
  if (h == 0) return;
  const float r = static_cast<float>(M_SQRT1_2);
  for (size_t i = 0; i < h; ++i) {
    const float lo = line[i], hi = line[h + i];
    scratch[2 * i] = (lo + hi) * r;
    scratch[2 * i + 1] = (lo - hi) * r;
  }
  std::memcpy(line.data(), scratch.data(), 2 * h * sizeof(float));
}

void Forward1d(WaveletFilter f, std::span<float> line, std::span<float> scratch) {
  switch (f) {
    case WaveletFilter::kHaar:
      return HaarForward1d(line, scratch);
    case WaveletFilter::kDaub4:
      return Daub4Forward1d(line, scratch);
    case WaveletFilter::kLeGall53:
      return LiftingForward1d(LeGall53Scheme(), line, scratch);
    case WaveletFilter::kCdf97:
      return LiftingForward1d(Cdf97Scheme(), line, scratch);
  }
}

void Inverse1d(WaveletFilter f, std::span<float> line, std::span<float> scratch) {
  switch (f) {
    case WaveletFilter::kHaar:
      return HaarInverse1d(line, scratch);
    case WaveletFilter::kDaub4:
      return Daub4Inverse1d(line, scratch);
    case WaveletFilter::kLeGall53:
      return LiftingInverse1d(LeGall53Scheme(), line, scratch);
    case WaveletFilter::kCdf97:
      return LiftingInverse1d(Cdf97Scheme(), line, scratch);
  }
}

}  // namespace wavebake
