#pragma once
// Power-of-two checks for the sizes the transforms need (cube faces, sample
// grids, tiles), with the range each caller allows. One definition instead
// of the hand-written (v & (v − 1)) == 0, which calls 0 a power of two.
#include <bit>

namespace wavebake {

constexpr bool IsPowerOfTwo(int v) {
  return v > 0 && std::has_single_bit(static_cast<unsigned>(v));
}

// A power of two in [lo, hi].
constexpr bool IsPowerOfTwoIn(int v, int lo, int hi) {
  return v >= lo && v <= hi && IsPowerOfTwo(v);
}

}  // namespace wavebake
