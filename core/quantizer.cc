#include "core/quantizer.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace wavebake {
namespace {

uint64_t Mix(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

int MaxQuantCode(int bits) { return (1 << (bits - 1)) - 1; }

int BitsForCode(int max_code) {
  return std::max(2, static_cast<int>(std::bit_width(static_cast<unsigned>(max_code))) + 1);
}

float DitherAt(uint64_t seed, uint64_t column, uint32_t position) {
  const uint64_t h = Mix(Mix(Mix(seed) ^ column) ^ position);
  return static_cast<float>(static_cast<double>(h >> 40) * 0x1p-24 - 0.5);
}

double LevelScaledMax(std::span<const float> values, std::span<const uint8_t> levels,
                      LevelScaling scaling) {
  double m = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    // v / k = v · 2^−exponent; powers of two are exact.
    const int e = LevelExponent(scaling, levels[i]);
    m = std::max(m, std::fabs(std::ldexp(static_cast<double>(values[i]), -e)));
  }
  return m;
}

float StepForMax(double max_abs, int max_code) {
  const double step = max_abs / max_code;
  // Rounded up so that the stored float step (the one decoding uses) still
  // keeps the largest value within max_code.
  float f = static_cast<float>(step);
  if (static_cast<double>(f) < step) f = std::nextafter(f, INFINITY);
  return f;
}

std::vector<int16_t> Quantize(std::span<const float> values, std::span<const uint32_t> positions,
                              std::span<const uint8_t> levels, LevelScaling scaling, float step,
                              int max_code, uint64_t seed, uint64_t column) {
  std::vector<int16_t> q(values.size(), 0);
  if (step == 0) return q;
  const double c = std::clamp(max_code, 1, kMaxStoredCode);
  for (size_t i = 0; i < values.size(); ++i) {
    const int e = LevelExponent(scaling, levels[i]);
    const double y = std::ldexp(static_cast<double>(values[i]), -e) / double{step};
    const double u = DitherAt(seed, column, positions[i]);
    q[i] = static_cast<int16_t>(std::clamp(std::round(y + u), -c, c));
  }
  return q;
}

void Dequantize(std::span<const int16_t> q, std::span<const uint32_t> positions,
                std::span<const uint8_t> levels, LevelScaling scaling, float step, uint64_t seed,
                uint64_t column, std::span<float> out) {
  for (size_t i = 0; i < q.size(); ++i) {
    if (step == 0) {
      out[i] = 0;
      continue;
    }
    const double u = DitherAt(seed, column, positions[i]);
    out[i] = static_cast<float>(
        std::ldexp((q[i] - u) * double{step}, LevelExponent(scaling, levels[i])));
  }
}

double QuantizationBound(float step, int level, LevelScaling scaling, int max_code) {
  return std::ldexp(double{step} * (0.5 + 0x1p-24 * (max_code + 0.5)),
                    LevelExponent(scaling, level));
}

}  // namespace wavebake
