#pragma once
// A cube texel seen meridian by meridian. Every meridian half-plane (fixed
// azimuth φ, latlong.h) cuts a texel in one arc: a segment of the line or ray
// the meridian projects to on the face plane, clipped to the texel's
// rectangle. So the texel is {(φ, μ = cos θ) : φ ∈ its azimuth range,
// μ ∈ At(φ)}; in (φ, μ) solid angle is plain area (dω = dμ dφ), which turns
// overlaps with lat-long pixels (rectangles in φ and μ) into 1D integrals.
#include <vector>

#include "core/directions/cubemap.h"

namespace wavebake {

struct MuInterval {
  double lo = 0, hi = 0;  // empty when lo >= hi
};

class TexelMeridians {
 public:
  TexelMeridians(const Cubemap& cube, int m);

  // Sorted azimuths, first and last bounding the texel, between which both
  // ends of At(φ) are smooth and monotone. The range is unwrapped: it may
  // run past π across the lat-long seam.
  const std::vector<double>& breakpoints() const { return breaks_; }
  MuInterval At(double phi) const;

 private:
  void InitSide();
  void InitCap();

  int face_;
  double s0_, s1_, t0_, t1_;  // the texel's rectangle in face coordinates [−1, 1]
  std::vector<double> breaks_;
};

}  // namespace wavebake
