#pragma once
// The lat-long (equirectangular) convention of every environment map in
// wavebake. It is the one of Debevec's light probes as published by USC ICT
// (and redistributed by Probulator), in the cubemap's world axes (Y up):
//
//   u = (x + 0.5) / width,   v = (y + 0.5) / height        (pixel centres)
//   θ = π v                  polar angle from +Y: row 0 is the zenith,
//                            the last row the nadir
//   φ = π (2u − 1)           azimuth, φ ∈ [−π, π)
//   d = (sin θ sin φ, cos θ, −sin θ cos φ)
//
// So the image centre (u = ½) looks down −Z ("forward"), u = ¾ is +X,
// u = ¼ is −X and the left/right seam (u = 0 ≡ 1) is +Z. Looking at −Z with
// +Y up, +X is on the right: the image is the view from inside the sphere.
#include "core/util/vec3.h"

namespace wavebake {

struct LatLong {
  double u = 0, v = 0;  // both in [0, 1]; u wraps around
};

Vec3 LatLongToDirection(LatLong p);
// d need not be normalized; the zero vector maps to the zenith.
LatLong DirectionToLatLong(Vec3 d);

// Exact solid angle of one pixel of row y in a width × height lat-long map:
// the band θ ∈ [π y/h, π (y+1)/h] has solid angle 2π (cos θ0 − cos θ1).
double LatLongPixelSolidAngle(int y, int width, int height);

}  // namespace wavebake
