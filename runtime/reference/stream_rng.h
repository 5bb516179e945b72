#pragma once
// The counter-based random streams of the Monte-Carlo references
// (runtime/reference/reference.h, runtime/reference/area_reference.h): SplitMix64 (Steele, Lea,
// Flood 2014) seeded by hash(job seed ⊕ domain, stream), one stream per
// sample, so a reference is bit-identical for any number of threads.
#include <cstdint>

namespace wavebake {

inline uint64_t SplitMix64Mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class StreamRng {
 public:
  // domain: a constant per reference, so two references never share draws.
  StreamRng(uint64_t seed, uint64_t domain, uint64_t stream)
      : state_(SplitMix64Mix(SplitMix64Mix(seed ^ domain) + stream)) {}
  // Uniform in [0, 1) on a 2^-53 grid.
  double Next01() {
    return static_cast<double>(SplitMix64Mix(state_ += 0x9e3779b97f4a7c15ull) >> 11) * 0x1p-53;
  }

 private:
  uint64_t state_;
};

}  // namespace wavebake
