#pragma once
// Helpers shared by the core wavelet tests: random images and norms computed
// independently of the code under test (double accumulation).
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "core/bake/bake_params.h"

namespace wavebake::testing {

inline std::vector<float> RandomImage(int width, int height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> dist(-1.0f, 1.0f);
  std::vector<float> img(static_cast<size_t>(width) * height);
  for (float& v : img) v = dist(rng);
  return img;
}

inline double Dot(std::span<const float> a, std::span<const float> b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += static_cast<double>(a[i]) * b[i];
  return s;
}

inline double MaxAbsDiff(std::span<const float> a, std::span<const float> b) {
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::fabs(double(a[i]) - b[i]));
  return m;
}

inline double MaxAbs(std::span<const float> a) {
  double m = 0;
  for (float v : a) m = std::max(m, std::fabs(double(v)));
  return m;
}

inline const char* FilterName(WaveletFilter f) {
  switch (f) {
    case WaveletFilter::kHaar:
      return "Haar";
    case WaveletFilter::kDaub4:
      return "Daub4";
    case WaveletFilter::kLeGall53:
      return "LeGall53";
    case WaveletFilter::kCdf97:
      return "Cdf97";
  }
  return "?";
}

constexpr WaveletFilter kAllFilters[] = {WaveletFilter::kHaar, WaveletFilter::kDaub4,
                                         WaveletFilter::kLeGall53, WaveletFilter::kCdf97};

}  // namespace wavebake::testing
