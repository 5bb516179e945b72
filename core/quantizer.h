#pragma once
// Scaling, subtractive dither and scalar quantization of one column's kept
// coefficients (DESIGN.md §1 "Scaling and quantization"; 4D paper §4.3).
//
// For kept coefficient i with value v_i at subband level l_i (core/subband.h,
// 0 = coarsest):
//   y_i   = v_i · 2^l_i / scale,     scale = max_i |v_i · 2^l_i|   (0 for an all-zero column)
//   q_i   = clamp(round(y_i·Q + u_i), −Q, Q),   Q = 2^(b−1) − 1,   b ∈ [2, 16]
//   v̂_i   = (q_i − u_i) / Q · scale / 2^l_i
// with u_i = DitherAt(seed, column, position_i) ∈ [−0.5, 0.5). Because the same
// u_i is subtracted again (subtractive dither), |v̂_i − v_i| ≤ ½ step and the
// error is uniform and independent of the signal instead of a fixed bias.
// round() is half away from zero (std::round); arithmetic is in double, v̂ is
// rounded to float once.
#include <cstdint>
#include <span>
#include <vector>

namespace wavebake {

struct QuantizedColumn {
  std::vector<int16_t> q;  // one per kept coefficient
  float scale = 0;
};

// Deterministic dither, reproducible with numpy uint64 arithmetic (wrapping):
//   mix(z):  z += 0x9E3779B97F4A7C15
//            z  = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9
//            z  = (z ^ (z >> 27)) * 0x94D049BB133111EB
//            return z ^ (z >> 31)                         (splitmix64 output step)
//   h = mix(mix(mix(seed) ^ column) ^ position)
//   u = (h >> 40) · 2^−24 − 0.5                           (24 bits: exact in float)
float DitherAt(uint64_t seed, uint64_t column, uint32_t position);

// values, positions (Mallat index of each kept coefficient) and levels are
// parallel arrays; bits ∈ [2, 16].
QuantizedColumn Quantize(std::span<const float> values, std::span<const uint32_t> positions,
                         std::span<const uint8_t> levels, int bits, uint64_t seed, uint64_t column);
// Writes v̂ into out (same length as q). A column with scale 0 dequantizes to 0.
void Dequantize(std::span<const int16_t> q, std::span<const uint32_t> positions,
                std::span<const uint8_t> levels, float scale, int bits, uint64_t seed,
                uint64_t column, std::span<float> out);

// Largest |v̂ − v| the quantizer can produce for a coefficient of this column
// scale, level and bit count: half a step, scale/(2Q)/2^l, plus the rounding of
// v̂ to float (≤ 2^−23 · scale / 2^l, since |v̂| ≤ (1 + 1/(2Q)) · scale / 2^l).
double QuantizationBound(float scale, int level, int bits);

}  // namespace wavebake
