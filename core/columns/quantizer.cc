#include "core/columns/quantizer.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace wavebake {
int MaxQuantCode(int bits) { return (1 << (bits - 1)) - 1; }

int BitsForCode(int max_code) {
  return std::max(2, static_cast<int>(std::bit_width(static_cast<unsigned>(max_code))) + 1);
}

float DitherAt(uint64_t seed, uint64_t column, uint32_t position) {
  return ColumnDither(seed, column).At(position);
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
  // The next float up, as std::nextafter(f, INFINITY) but without the libm
  // call: f is finite and ≥ 0 here, where the next bit pattern is the next float.
  if (static_cast<double>(f) < step) f = std::bit_cast<float>(std::bit_cast<uint32_t>(f) + 1);
  return f;
}

namespace {

// std::round (half away from zero) for |x| < 2^62, without the libm call:
// x − trunc(x) is exact there. The two comparisons are summed as integers:
// as doubles, the compiler branched on one of them, and with dithered
// inputs that branch goes either way at random (a misprediction every
// other value, an eighth of FINALIZE's quantization time).
double RoundHalfAway(double x) {
  const int64_t t = static_cast<int64_t>(x);
  const double f = x - static_cast<double>(t);
  return static_cast<double>(t + int64_t{f >= 0.5} - int64_t{f <= -0.5});
}

// 2^e for the level exponents (e ∈ [−31, 0]): multiplying by an exact power
// of two rounds like ldexp.
double Pow2(int e) { return std::ldexp(1.0, e); }

// The quantizer of the header and, with weights, Σ ((v̂_i − v_i)·w_i)² with
// v̂_i decoded exactly as Dequantize does (empty weights: no error computed).
double QuantizeKernel(std::span<const float> values, std::span<const uint32_t> positions,
                      std::span<const uint8_t> levels, LevelScaling scaling, float step,
                      int max_code, uint64_t seed, uint64_t column, std::span<const float> weights,
                      std::span<int16_t> q) {
  if (step == 0) {
    std::fill(q.begin(), q.begin() + values.size(), int16_t{0});
    double error = 0;  // every value decodes to 0
    if (weights.empty()) return error;
    for (size_t i = 0; i < values.size(); ++i) {
      const double d = (0.0 - double{values[i]}) * weights[positions[i]];
      error += d * d;
    }
    return error;
  }
  const ColumnDither dither(seed, column);
  const double c = std::clamp(max_code, 1, kMaxStoredCode);
  double error = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    const int e = LevelExponent(scaling, levels[i]);
    const double u = dither.At(positions[i]);
    const double v = e == 0 ? double{values[i]} : double{values[i]} * Pow2(-e);
    // Clamped first (to ±(C+1), which rounds and clamps like anything beyond)
    // so that the rounding stays in range for any value.
    const double y = std::clamp(v / double{step} + u, -c - 1, c + 1);
    q[i] = static_cast<int16_t>(std::clamp(RoundHalfAway(y), -c, c));
    if (weights.empty()) continue;
    const double back = (q[i] - u) * double{step};
    const float decoded = static_cast<float>(e == 0 ? back : back * Pow2(e));
    const double d = (double{decoded} - double{values[i]}) * weights[positions[i]];
    error += d * d;
  }
  return error;
}

}  // namespace

void QuantizeInto(std::span<const float> values, std::span<const uint32_t> positions,
                  std::span<const uint8_t> levels, LevelScaling scaling, float step, int max_code,
                  uint64_t seed, uint64_t column, std::span<int16_t> q) {
  QuantizeKernel(values, positions, levels, scaling, step, max_code, seed, column, {}, q);
}

double QuantizeWithError(std::span<const float> values, std::span<const uint32_t> positions,
                         std::span<const uint8_t> levels, LevelScaling scaling, float step,
                         int max_code, uint64_t seed, uint64_t column,
                         std::span<const float> weights, std::span<int16_t> q) {
  return QuantizeKernel(values, positions, levels, scaling, step, max_code, seed, column, weights,
                        q);
}

std::vector<int16_t> Quantize(std::span<const float> values, std::span<const uint32_t> positions,
                              std::span<const uint8_t> levels, LevelScaling scaling, float step,
                              int max_code, uint64_t seed, uint64_t column) {
  std::vector<int16_t> q(values.size(), 0);
  QuantizeInto(values, positions, levels, scaling, step, max_code, seed, column, q);
  return q;
}

void Dequantize(std::span<const int16_t> q, std::span<const uint32_t> positions,
                std::span<const uint8_t> levels, LevelScaling scaling, float step, uint64_t seed,
                uint64_t column, std::span<float> out) {
  if (step == 0) {
    std::fill(out.begin(), out.begin() + q.size(), 0.0f);
    return;
  }
  const ColumnDither dither(seed, column);
  for (size_t i = 0; i < q.size(); ++i) {
    const double u = dither.At(positions[i]);
    const int e = LevelExponent(scaling, levels[i]);
    const double v = (q[i] - u) * double{step};
    out[i] = static_cast<float>(e == 0 ? v : v * Pow2(e));
  }
}

double QuantizationBound(float step, int level, LevelScaling scaling, int max_code) {
  return std::ldexp(double{step} * (0.5 + 0x1p-24 * (max_code + 0.5)),
                    LevelExponent(scaling, level));
}

}  // namespace wavebake
