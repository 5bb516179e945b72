#pragma once
// The source side of near-field relighting (Sun & Ramamoorthi §5.2, §5.3.3,
// §5.4.2): an area light drawn into an R×R image over the axis-aligned
// bounding box of its (rotated) rectangle in the light plane — rotation and
// texture edits happen here, in the pixel domain, once per frame — then
// row-transformed (non-standard Haar) into the source coefficients F_i, of
// which the source-level truncation keeps the largest.
#include <span>
#include <vector>

#include "core/products/affine_propagation.h"
#include "runtime/near_field/area_light.h"

namespace wavebake {

struct LightCanvas {
  int res = 0;            // R
  double s0 = 0, t0 = 0;  // lower corner in the plane's (s, t) coordinates
  double extent_s = 1, extent_t = 1;
  double height = 0;          // of the light plane along the axis
  std::vector<float> rgb;     // [R*R*3] mean radiance per texel; texel (x, y) covers
                              // s0 + [x, x+1)·extent_s/R, t0 + [y, y+1)·extent_t/R
  std::vector<float> coeffs;  // [3][R*R] the row transform of each channel

  // Eq. 29: a point at in-plane (ps, pt) and distance z > 0 below the plane
  // sees, through face coordinate v ∈ [0,1] of a face of size S, canvas
  // coordinate q = s v + o per axis.
  AffineMap2d MapAt(double ps, double pt, double z, double face_size) const;
};

// Each canvas texel is the mean of supersample² regularly placed points of
// the light (area_light.h); exact for an unrotated light whose texture has R
// pixels per edge (or none).
LightCanvas DrawLight(const AreaLight& light, int supersample = 4);

// Source-level truncation (§5.3.3): the ceil(fraction·R²) coefficients of
// largest RGB norm (≥ 1, nonzero only; ties: lower index), as SourceTerms.
std::vector<SourceTerm> SelectSources(const LightCanvas& canvas, double fraction);

}  // namespace wavebake
