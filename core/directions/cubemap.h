#pragma once
// Cubemap of light directions, DESIGN.md §1: 6 faces of N×N texels, face
// order +X −X +Y −Y +Z −Z, OpenGL orientation, texel centres at (i+0.5)/N,
// light index m = face*N*N + y*N + x, exact texel solid angles.
#include <array>

#include "core/util/vec3.h"

namespace wavebake {

enum CubeFace : int { kPosX = 0, kNegX, kPosY, kNegY, kPosZ, kNegZ };

struct Texel {
  int face = 0, x = 0, y = 0;
  constexpr bool operator==(const Texel&) const = default;
};

class Cubemap {
 public:
  // n: texels per face edge, a power of two in [1, 256] (the bake checks 8..256).
  explicit Cubemap(int n);

  int n() const { return n_; }
  int size() const { return 6 * n_ * n_; }  // M, the number of light directions

  int Index(Texel t) const { return (t.face * n_ + t.y) * n_ + t.x; }
  Texel TexelOf(int m) const;

  // Unit direction through face coordinates (s, t) ∈ [0,1]², OpenGL convention:
  // s grows with texel x, t grows with texel y.
  static Vec3 FaceDirection(int face, double s, double t);
  // The same direction in double, not normalized: the point on the face of
  // the cube [-1,1]³ (texel corners for exact integrals, core/directions/texel_irradiance.h).
  static std::array<double, 3> FacePoint(int face, double s, double t);
  Vec3 TexelCenter(int m) const;
  // Solid angle of texel m, exact (corner formula atan2(xy, sqrt(x²+y²+1))).
  double SolidAngle(int m) const;
  // Texel whose square contains direction d (d need not be normalized).
  int Lookup(Vec3 d) const;

 private:
  int n_;
};

}  // namespace wavebake
