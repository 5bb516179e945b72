#include "core/directions/cubemap.h"

#include <algorithm>
#include <cmath>

namespace wavebake {

Cubemap::Cubemap(int n) : n_(n) {}

Texel Cubemap::TexelOf(int m) const {
  const int per_face = n_ * n_;
  const int r = m % per_face;
  return {m / per_face, r % n_, r / n_};
}

// OpenGL spec table 3.21 (major axis → sc, tc), inverted: for a face and
// sc, tc ∈ [-1,1] the (unnormalized) direction is the major axis plus the two
// minor components. One table for the float directions and the double points.
namespace {
template <class T>
std::array<T, 3> FaceAxes(int face, T sc, T tc) {
  switch (face) {
    case kPosX:
      return {1, -tc, -sc};
    case kNegX:
      return {-1, -tc, sc};
    case kPosY:
      return {sc, 1, tc};
    case kNegY:
      return {sc, -1, -tc};
    case kPosZ:
      return {sc, -tc, 1};
    default:
      return {-sc, -tc, -1};
  }
}
}  // namespace

Vec3 Cubemap::FaceDirection(int face, double s, double t) {
  const auto d = FaceAxes(face, static_cast<float>(2 * s - 1), static_cast<float>(2 * t - 1));
  return Normalize(Vec3{d[0], d[1], d[2]});
}

std::array<double, 3> Cubemap::FacePoint(int face, double s, double t) {
  return FaceAxes(face, 2 * s - 1, 2 * t - 1);
}

Vec3 Cubemap::TexelCenter(int m) const {
  const Texel t = TexelOf(m);
  return FaceDirection(t.face, (t.x + 0.5) / n_, (t.y + 0.5) / n_);
}

namespace {
// Solid angle of the face region [0,x]×[0,y] in face-plane coordinates at
// distance 1: the standard corner formula.
double CornerArea(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1)); }
}  // namespace

double Cubemap::SolidAngle(int m) const {
  const Texel t = TexelOf(m);
  const double x0 = 2.0 * t.x / n_ - 1, x1 = 2.0 * (t.x + 1) / n_ - 1;
  const double y0 = 2.0 * t.y / n_ - 1, y1 = 2.0 * (t.y + 1) / n_ - 1;
  return CornerArea(x1, y1) - CornerArea(x0, y1) - CornerArea(x1, y0) + CornerArea(x0, y0);
}

int Cubemap::Lookup(Vec3 d) const {
  const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  int face;
  float sc, tc, ma;
  if (ax >= ay && ax >= az) {
    face = d.x >= 0 ? kPosX : kNegX;
    ma = ax;
    sc = d.x >= 0 ? -d.z : d.z;
    tc = -d.y;
  } else if (ay >= az) {
    face = d.y >= 0 ? kPosY : kNegY;
    ma = ay;
    sc = d.x;
    tc = d.y >= 0 ? d.z : -d.z;
  } else {
    face = d.z >= 0 ? kPosZ : kNegZ;
    ma = az;
    sc = d.z >= 0 ? d.x : -d.x;
    tc = -d.y;
  }
  const double s = 0.5 * (sc / ma + 1), t = 0.5 * (tc / ma + 1);
  const int x = std::clamp(static_cast<int>(s * n_), 0, n_ - 1);
  const int y = std::clamp(static_cast<int>(t * n_), 0, n_ - 1);
  return Index({face, x, y});
}

}  // namespace wavebake
