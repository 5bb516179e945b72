#pragma once
// Deterministic test values covering each dtype's whole bit range (negative
// numbers, extremes, and for floats also NaN/inf bit patterns), so a round
// trip that changes any bit is caught. Compare with BitEqual, not ==.
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace wavebake::testing {

inline uint64_t Mix(uint64_t x) {  // splitmix64 finalizer
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

template <class T>
std::vector<T> TestValues(size_t n, uint64_t seed) {
  std::vector<T> v(n);
  for (size_t i = 0; i < n; ++i) {
    const uint64_t bits = Mix(seed * 1000003 + i);
    std::memcpy(&v[i], &bits, sizeof(T));
  }
  return v;
}

template <class T>
bool BitEqual(std::span<const T> a, std::span<const T> b) {
  // memcmp of empty spans would pass null pointers (undefined, UBSan says).
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}

}  // namespace wavebake::testing
