#pragma once
// Most values of a transport column are exactly 0 and come in runs (masked
// cells, directions below the horizon, occluded ones): passes that only
// accumulate over nonzero values skip them four at a time. A zero adds
// nothing to a sum of squares or to a histogram, so skipping changes no
// result, while a dependent chain of adds over every value (a double add per
// value, ~4 cycles) would cost as much as the rest of the pass.
#include <cstdint>
#include <cstring>

namespace wavebake {

// v[0..3] are all ±0.
inline bool ZeroQuad(const float* v) {
  uint32_t bits[4];
  std::memcpy(bits, v, sizeof bits);
  return ((bits[0] | bits[1] | bits[2] | bits[3]) & 0x7fffffffu) == 0;
}

// f(i) for every i in [0, n) except those in quads of zeros.
template <class F>
void ForNonzeroQuads(const float* v, size_t n, F f) {
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    if (ZeroQuad(v + i)) continue;
    f(i), f(i + 1), f(i + 2), f(i + 3);
  }
  for (; i < n; ++i) f(i);
}

// Σ v² in double, in a fixed order: four partial sums, value i going to sum
// i mod 4, combined as (s0 + s1) + (s2 + s3). One running sum would be a
// chain of dependent adds, ~4 cycles per nonzero value (measured: 1 s of a
// 65536-row bake's CPU for the row energies alone); four chains run side by
// side. Deterministic like any fixed order, but not the bits of a single
// running sum.
inline double SumOfSquares(const float* v, size_t n) {
  double s[4] = {0, 0, 0, 0};
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    if (ZeroQuad(v + i)) continue;
    for (int j = 0; j < 4; ++j) s[j] += double{v[i + j]} * v[i + j];
  }
  for (; i < n; ++i) s[i % 4] += double{v[i]} * v[i];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

}  // namespace wavebake
