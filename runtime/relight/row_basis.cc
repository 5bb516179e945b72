#include "runtime/relight/row_basis.h"

#include <bit>
#include <cstddef>

#include "core/directions/cubemap.h"
#include "core/wavelets/subband.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

// Applies `transform` to each N×N channel image of each face of rgb[3M].
template <typename Transform>
void ForEachFacePlane(int n, std::span<float> rgb, const Transform& transform) {
  const size_t per_face = static_cast<size_t>(n) * n;
  std::vector<float> plane(per_face);
  for (int face = 0; face < 6; ++face) {
    float* base = rgb.data() + face * per_face * 3;
    for (int c = 0; c < 3; ++c) {
      for (size_t i = 0; i < per_face; ++i) plane[i] = base[3 * i + c];
      transform(std::span<float>(plane));
      for (size_t i = 0; i < per_face; ++i) base[3 * i + c] = plane[i];
    }
  }
}

}  // namespace

void RowTransformCube(WaveletFilter filter, int n, std::span<float> rgb) {
  const int depth = MaxDepth(n, n);
  ForEachFacePlane(n, rgb, [&](std::span<float> p) { Forward2d(filter, p, n, n, depth); });
}

void InverseRowTransformCube(WaveletFilter filter, int n, std::span<float> rgb) {
  const int depth = MaxDepth(n, n);
  ForEachFacePlane(n, rgb, [&](std::span<float> p) { Inverse2d(filter, p, n, n, depth); });
}

int RowBand(int x, int y) {
  const int level = RowLevel(x, y);
  return level > 0 ? level - 1 : 0;
}

int RowBandCount(int n) { return std::bit_width(static_cast<unsigned>(n)) - 1; }

std::vector<float> SupportSolidAngles(int n) {
  const Cubemap cube(n);
  // Summed-area table of texel solid angles per face (the same on every face
  // by symmetry, but computing each keeps this obviously right).
  const int stride = n + 1;
  std::vector<double> sat(static_cast<size_t>(6) * stride * stride, 0.0);
  auto at = [&](int face, int x, int y) -> double& {
    return sat[(static_cast<size_t>(face) * stride + y) * stride + x];
  };
  for (int face = 0; face < 6; ++face) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        at(face, x + 1, y + 1) = cube.SolidAngle(cube.Index({face, x, y})) + at(face, x, y + 1) +
                                 at(face, x + 1, y) - at(face, x, y);
      }
    }
  }
  std::vector<float> out(cube.size());
  for (int m = 0; m < cube.size(); ++m) {
    const Texel t = cube.TexelOf(m);
    const int level = RowLevel(t.x, t.y);
    // Level l ≥ 1 holds 2^(l−1) × 2^(l−1) wavelets per orientation, each on a
    // block of N / 2^(l−1) texels; level 0 (scaling) and level 1 cover the face.
    const int blocks = level > 0 ? 1 << (level - 1) : 1;
    const int side = n / blocks;
    const int bx = t.x & (blocks - 1), by = t.y & (blocks - 1);
    const int x0 = bx * side, y0 = by * side, x1 = x0 + side, y1 = y0 + side;
    out[m] = static_cast<float>(at(t.face, x1, y1) - at(t.face, x0, y1) - at(t.face, x1, y0) +
                                at(t.face, x0, y0));
  }
  return out;
}

}  // namespace wavebake
