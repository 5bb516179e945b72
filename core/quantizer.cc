#include "core/quantizer.h"

#include <algorithm>
#include <cmath>

namespace wavebake {
namespace {

uint64_t Mix(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

int MaxCode(int bits) { return (1 << (bits - 1)) - 1; }

}  // namespace

float DitherAt(uint64_t seed, uint64_t column, uint32_t position) {
  const uint64_t h = Mix(Mix(Mix(seed) ^ column) ^ position);
  return static_cast<float>(static_cast<double>(h >> 40) * 0x1p-24 - 0.5);
}

QuantizedColumn Quantize(std::span<const float> values, std::span<const uint32_t> positions,
                         std::span<const uint8_t> levels, int bits, uint64_t seed,
                         uint64_t column) {
  QuantizedColumn out;
  out.q.assign(values.size(), 0);
  double scale = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    scale = std::max(scale, std::fabs(std::ldexp(static_cast<double>(values[i]), levels[i])));
  }
  // Stored as float, rounded up so that |y| ≤ 1 still holds exactly when we
  // normalize by the stored number (the one dequantization will use).
  out.scale = static_cast<float>(scale);
  if (static_cast<double>(out.scale) < scale) out.scale = std::nextafter(out.scale, INFINITY);
  if (out.scale == 0) return out;
  const int qmax = MaxCode(bits);
  for (size_t i = 0; i < values.size(); ++i) {
    const double y = std::ldexp(static_cast<double>(values[i]), levels[i]) / out.scale;
    const double u = DitherAt(seed, column, positions[i]);
    const double r = std::round(y * qmax + u);
    out.q[i] = static_cast<int16_t>(std::clamp(r, -double(qmax), double(qmax)));
  }
  return out;
}

void Dequantize(std::span<const int16_t> q, std::span<const uint32_t> positions,
                std::span<const uint8_t> levels, float scale, int bits, uint64_t seed,
                uint64_t column, std::span<float> out) {
  const int qmax = MaxCode(bits);
  for (size_t i = 0; i < q.size(); ++i) {
    if (scale == 0) {
      out[i] = 0;
      continue;
    }
    const double u = DitherAt(seed, column, positions[i]);
    out[i] = static_cast<float>(std::ldexp((q[i] - u) / qmax * scale, -levels[i]));
  }
}

double QuantizationBound(float scale, int level, int bits) {
  return std::ldexp(static_cast<double>(scale) * (0.5 / MaxCode(bits) + 0x1p-23), -level);
}

}  // namespace wavebake
