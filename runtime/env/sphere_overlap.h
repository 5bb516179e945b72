#pragma once
// How much of each lat-long pixel lies in each cubemap texel: the solid
// angles |p ∩ m| as a sparse matrix. Its sums over texels are the pixels'
// solid angles and its sums over pixels the texels' (both to ~1e-12), so
// resampling through it keeps constants and ∫ L dω, even for a source of a
// single pixel, which sampling in either direction cannot promise.
//
// Computed, not sampled: in (φ, μ = cos θ) solid angle is area and a pixel
// is a rectangle; a texel is, meridian by meridian, one μ-interval
// (texel_meridians.h). For each texel the azimuth range is cut at pixel
// columns and at the texel's own kinks, each piece is integrated with
// Gauss–Legendre nodes, and at each node the μ-interval is split exactly
// among the pixel rows.
#include <span>
#include <vector>

#include "core/directions/cubemap.h"

namespace wavebake {

class SphereOverlap {
 public:
  SphereOverlap(int width, int height, const Cubemap& cube);

  // [3 * cube.size()] texel means from [3 * width * height] pixel values.
  std::vector<float> CubeFromLatLong(std::span<const float> latlong_rgb) const;
  // [3 * width * height] pixel means from [3 * cube.size()] texel values.
  std::vector<float> LatLongFromCube(std::span<const float> cube_rgb) const;

  // Σ over pixels of texel m's overlaps (≈ its solid angle), and likewise
  // for pixel p (row-major index).
  double TexelArea(int m) const { return texel_area_[m]; }
  double PixelArea(int p) const { return pixel_area_[p]; }

 private:
  // CSR by texel: entries first_[m] .. first_[m+1] − 1.
  std::vector<int> first_, pixel_;
  std::vector<double> area_, texel_area_, pixel_area_;
};

}  // namespace wavebake
