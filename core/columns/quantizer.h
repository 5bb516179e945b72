#pragma once
// Scaling, subtractive dither and scalar quantization of one column's kept
// coefficients (DESIGN.md §1 "Scaling and quantization"; 4D paper §4.3).
//
// For kept coefficient i with value v_i at subband level l_i (core/wavelets/subband.h,
// 0 = coarsest) and the column's quantization step Δ (stored as `scale`):
//   k_i   = 2^−l_i (LevelScaling::kPaper)  or  1 (kUniform)
//   q_i   = clamp(round(v_i / (k_i·Δ) + u_i), −C, C),   C ≤ 32767 the column's largest code
//   v̂_i   = (q_i − u_i) · Δ · k_i                                   (the one decode formula)
// with u_i = DitherAt(seed, column, position_i) ∈ [−0.5, 0.5). Because the same
// u_i is subtracted again (subtractive dither), |v̂_i − v_i| ≤ ½ Δ·k_i and the
// error is uniform and independent of the signal instead of a fixed bias.
// round() is half away from zero (std::round); arithmetic is in double, v̂ is
// rounded to float once. Δ = 0 decodes to 0 (an empty column).
//
// kPaper with b bits is the paper's scheme: Δ = max_i |v_i / k_i| / Q_b,
// Q_b = 2^(b−1) − 1, i.e. the column normalized by its max and quantized to b
// bits. kUniform spends no extra bits on fine levels: for orthonormal filters
// the MSE weight of every coefficient is 1, so one step for all of them is the
// high-rate optimal allocation (worker/columns/finalize.h picks the steps).
#include <cstdint>
#include <span>
#include <vector>

#include "core/bake/bake_params.h"

namespace wavebake {

// The largest code an int16 store holds; a step must keep |q| ≤ this.
inline constexpr int kMaxStoredCode = 32767;

// Deterministic dither, reproducible with numpy uint64 arithmetic (wrapping):
//   mix(z):  z += 0x9E3779B97F4A7C15
//            z  = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9
//            z  = (z ^ (z >> 27)) * 0x94D049BB133111EB
//            return z ^ (z >> 31)                         (splitmix64 output step)
//   h = mix(mix(mix(seed) ^ column) ^ position)
//   u = (h >> 40) · 2^−24 − 0.5                           (24 bits: exact in float)
float DitherAt(uint64_t seed, uint64_t column, uint32_t position);

// DitherAt of one column, its first two mixes done once (inline: the
// quantizer and the decoder call it once per value).
class ColumnDither {
 public:
  ColumnDither(uint64_t seed, uint64_t column) : base_(Mix(Mix(seed) ^ column)) {}
  float At(uint32_t position) const {
    const uint64_t h = Mix(base_ ^ position);
    return static_cast<float>(static_cast<double>(h >> 40) * 0x1p-24 - 0.5);
  }
  static uint64_t Mix(uint64_t z) {  // the splitmix64 step above
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

 private:
  uint64_t base_;
};

// k_i as a power-of-two exponent: −l for kPaper, 0 for kUniform.
inline int LevelExponent(LevelScaling s, int level) {
  return s == LevelScaling::kPaper ? -level : 0;
}

// max_i |v_i / k_i|: the magnitude the column's largest code must reach.
double LevelScaledMax(std::span<const float> values, std::span<const uint8_t> levels,
                      LevelScaling scaling);

// The smallest float step Δ with max_abs / Δ ≤ max_code (0 for max_abs 0).
float StepForMax(double max_abs, int max_code);

// values, positions (Mallat index of each kept coefficient) and levels are
// parallel arrays; max_code ∈ [1, kMaxStoredCode] clamps the codes.
std::vector<int16_t> Quantize(std::span<const float> values, std::span<const uint32_t> positions,
                              std::span<const uint8_t> levels, LevelScaling scaling, float step,
                              int max_code, uint64_t seed, uint64_t column);
// The same into q (values.size() long), allocating nothing.
void QuantizeInto(std::span<const float> values, std::span<const uint32_t> positions,
                  std::span<const uint8_t> levels, LevelScaling scaling, float step, int max_code,
                  uint64_t seed, uint64_t column, std::span<int16_t> q);
// QuantizeInto, returning the error energy Σ ((v̂_i − v_i)·w_i)² of the
// codes as Dequantize decodes them (w = weights[positions[i]]).
double QuantizeWithError(std::span<const float> values, std::span<const uint32_t> positions,
                         std::span<const uint8_t> levels, LevelScaling scaling, float step,
                         int max_code, uint64_t seed, uint64_t column,
                         std::span<const float> weights, std::span<int16_t> q);
// Writes v̂ into out (same length as q).
void Dequantize(std::span<const int16_t> q, std::span<const uint32_t> positions,
                std::span<const uint8_t> levels, LevelScaling scaling, float step, uint64_t seed,
                uint64_t column, std::span<float> out);

// Largest |v̂ − v| the quantizer can produce for an unclamped coefficient of
// this step and level: half a step, Δ·k/2, plus the rounding of v̂ to float
// (≤ 2^−24·|v̂| with |v̂| ≤ (C + ½)·Δ·k).
double QuantizationBound(float step, int level, LevelScaling scaling,
                         int max_code = kMaxStoredCode);

// Q_b = 2^(b−1) − 1, the largest code of b-bit signed quantization.
int MaxQuantCode(int bits);
// Bits of a signed code of magnitude up to `max_code`: bit_width + sign.
int BitsForCode(int max_code);

}  // namespace wavebake
