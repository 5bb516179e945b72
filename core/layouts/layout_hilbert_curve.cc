#include "core/layouts/layout_hilbert_curve.h"

#include <algorithm>
#include <utility>

namespace wavebake {
namespace {

// Position d along the Hilbert curve of an n×n square (n a power of two) to
// (x, y): peel two bits of d per level, rotating/reflecting the sub-square so
// each quadrant's curve starts where the previous one ended.
void CurvePoint(int n, int64_t d, int* x, int* y) {
  *x = *y = 0;
  for (int s = 1; s < n; s *= 2) {
    const int rx = static_cast<int>(1 & (d / 2));
    const int ry = static_cast<int>(1 & (d ^ rx));
    if (ry == 0) {
      if (rx == 1) {
        *x = s - 1 - *x;
        *y = s - 1 - *y;
      }
      std::swap(*x, *y);
    }
    *x += s * rx;
    *y += s * ry;
    d /= 4;
  }
}

}  // namespace

std::vector<int32_t> HilbertCurveCells(int width, int height) {
  const int side = std::min(width, height);
  const int blocks = std::max(width, height) / side;
  std::vector<int32_t> cells;
  cells.reserve(static_cast<size_t>(width) * height);
  for (int b = 0; b < blocks; ++b) {
    for (int64_t d = 0; d < int64_t{side} * side; ++d) {
      int x, y;
      CurvePoint(side, d, &x, &y);
      // Each block's curve runs (0,0) → (side−1,0): along the long side the
      // next block starts right after. Tall grids transpose the curve.
      if (width >= height) {
        cells.push_back(y * width + b * side + x);
      } else {
        cells.push_back((b * side + x) * width + y);
      }
    }
  }
  return cells;
}

uint64_t HilbertKey3(uint32_t x, uint32_t y, uint32_t z, int bits) {
  // J. Skilling, "Programming the Hilbert curve" (AIP Conf. Proc. 707, 2004):
  // turn the axes into the "transposed" Hilbert index in place...
  uint32_t p[3] = {x, y, z};
  const uint32_t top = 1u << (bits - 1);
  for (uint32_t q = top; q > 1; q >>= 1) {
    const uint32_t low = q - 1;
    for (uint32_t& c : p) {
      if (c & q) {
        p[0] ^= low;  // invert the low bits of the first axis
      } else {
        const uint32_t t = (p[0] ^ c) & low;  // exchange low bits with the first axis
        p[0] ^= t;
        c ^= t;
      }
    }
  }
  p[1] ^= p[0];  // Gray encode
  p[2] ^= p[1];
  uint32_t t = 0;
  for (uint32_t q = top; q > 1; q >>= 1)
    if (p[2] & q) t ^= q - 1;
  for (uint32_t& c : p) c ^= t;
  // ...whose bits, interleaved from the top, are the index.
  uint64_t key = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (uint32_t c : p) key = (key << 1) | ((c >> b) & 1u);
  return key;
}

}  // namespace wavebake
