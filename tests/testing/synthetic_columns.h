#pragma once
// A synthetic transport matrix for column-stage tests (core's depth search,
// worker's TRANSFORM_COLUMNS and FINALIZE): per column, smooth lighting, a
// few isolated spikes, or a smooth field cut by a hard shadow edge plus a
// spike, reproducible from the column index alone. Header-only: every test
// directory is its own binary.
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>

namespace wavebake::test_support {

// Value of cell (x, y) of light column m in a synthetic W×H matrix.
using ColumnImage = std::function<float(int column, int x, int y)>;

// What the synthetic column m is (column % 4, with every 16th column empty).
enum class SyntheticKind { kSmooth, kSpiky, kMixed, kEmpty };

namespace synthetic_detail {

inline uint64_t Hash(uint64_t z) {  // splitmix64: reproducible parameters per column
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) from the k-th hash of a column.
inline double Uniform(int column, int k) {
  return double(Hash(Hash(uint64_t(column)) ^ uint64_t(k)) >> 11) * 0x1p-53;
}

inline float Smooth(int m, int x, int y, int w, int h) {
  const double a = 0.5 + 0.5 * Uniform(m, 1), b = 0.5 + 0.5 * Uniform(m, 2);
  const double phase = Uniform(m, 3), two_pi = 2 * std::numbers::pi;
  return float(0.5 + 0.3 * std::sin(two_pi * (a * (x + 0.5) / w + phase)) *
                         std::cos(two_pi * b * (y + 0.5) / h));
}

inline float Spikes(int m, int x, int y, int w, int h, int count) {
  float v = 0;
  for (int k = 0; k < count; ++k) {
    const int sx = int(Uniform(m, 10 + 3 * k) * w), sy = int(Uniform(m, 11 + 3 * k) * h);
    const double amp = 2 + 2 * Uniform(m, 12 + 3 * k);
    if (sx == x && sy == y) v += float(k % 2 == 0 ? amp : -amp);
  }
  return v;
}

inline float Shadowed(int m, int x, int y, int w, int h) {
  const double theta = 2 * std::numbers::pi * Uniform(m, 20);
  const double d = (x - w / 2.0) * std::cos(theta) + (y - h / 2.0) * std::sin(theta);
  return d > (Uniform(m, 21) - 0.5) * w / 2 ? Smooth(m, x, y, w, h) : 0.0f;
}

}  // namespace synthetic_detail

inline SyntheticKind KindOf(int column) {
  if (column % 16 == 3) return SyntheticKind::kEmpty;
  switch (column % 4) {
    case 0:
      return SyntheticKind::kSmooth;
    case 1:
      return SyntheticKind::kSpiky;
    case 2:
      return SyntheticKind::kMixed;
    default:
      return SyntheticKind::kSmooth;
  }
}

inline ColumnImage SyntheticMatrix(int width, int height) {
  using namespace synthetic_detail;
  return [width, height](int m, int x, int y) -> float {
    switch (KindOf(m)) {
      case SyntheticKind::kSmooth:
        return Smooth(m, x, y, width, height);
      case SyntheticKind::kSpiky:
        return Spikes(m, x, y, width, height, 3);
      case SyntheticKind::kMixed:
        return Shadowed(m, x, y, width, height) + Spikes(m, x, y, width, height, 1);
      case SyntheticKind::kEmpty:
        return 0.0f;
    }
    return 0.0f;
  };
}

}  // namespace wavebake::test_support
