#include "core/directions/texel_irradiance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace wavebake {
namespace {

using D3 = std::array<double, 3>;

D3 Sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
D3 Add(const D3& a, const D3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
D3 Scale(const D3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double Dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 Cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double Norm(const D3& a) { return std::sqrt(Dot(a, a)); }

// A convex polygon on the sphere as points on rays from the origin (any
// positive scale per vertex: an edge is the arc the chord projects to).
struct Polygon {
  std::array<D3, 5> v;  // a quadrilateral clipped by one plane has at most 5 corners
  int n = 0;
};

Polygon TexelQuad(const Cubemap& cubemap, int m) {
  const Texel t = cubemap.TexelOf(m);
  const double k = cubemap.n(), s0 = t.x / k, s1 = (t.x + 1) / k, t0 = t.y / k, t1 = (t.y + 1) / k;
  Polygon p;
  p.v = {Cubemap::FacePoint(t.face, s0, t0), Cubemap::FacePoint(t.face, s1, t0),
         Cubemap::FacePoint(t.face, s1, t1), Cubemap::FacePoint(t.face, s0, t1)};
  p.n = 4;
  return p;
}

// ∫_P ω dω by Lambert's formula, oriented so that it points into P.
D3 LambertVector(const Polygon& p) {
  D3 sum{0, 0, 0}, centroid{0, 0, 0};
  for (int i = 0; i < p.n; ++i) {
    const D3 a = Scale(p.v[i], 1 / Norm(p.v[i]));
    const D3 b = Scale(p.v[(i + 1) % p.n], 1 / Norm(p.v[(i + 1) % p.n]));
    const D3 c = Cross(a, b);
    const double sin_theta = Norm(c);
    if (sin_theta == 0) continue;  // a repeated corner: no edge
    const double theta = std::atan2(sin_theta, Dot(a, b));
    sum = Add(sum, Scale(c, 0.5 * theta / sin_theta));
    centroid = Add(centroid, a);
  }
  // The corner order fixes the sign; every direction inside P has a
  // positive dot product with the true vector.
  return Dot(sum, centroid) < 0 ? Scale(sum, -1) : sum;
}

// Sutherland–Hodgman against the half-space n·x ≥ 0 (a plane through the
// origin, so the cut points of a chord project onto the horizon arc).
Polygon ClipToHemisphere(const Polygon& in, const D3& n) {
  Polygon out;
  for (int i = 0; i < in.n; ++i) {
    const D3& a = in.v[i];
    const D3& b = in.v[(i + 1) % in.n];
    const double da = Dot(n, a), db = Dot(n, b);
    if (da >= 0) out.v[out.n++] = a;
    if ((da >= 0) != (db >= 0)) out.v[out.n++] = Add(a, Scale(Sub(b, a), da / (da - db)));
  }
  return out;
}

}  // namespace

std::vector<Vec3> TexelIrradianceVectors(const Cubemap& cubemap) {
  std::vector<Vec3> phi(cubemap.size());
  for (int m = 0; m < cubemap.size(); ++m) {
    const D3 v = Scale(LambertVector(TexelQuad(cubemap, m)), 1 / std::numbers::pi);
    phi[m] = {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
  }
  return phi;
}

double ClippedTexelIrradiance(const Cubemap& cubemap, int m, Vec3 n) {
  // The orientation is the whole texel's: a clipped sliver may be too thin
  // for its own centroid test.
  const D3 whole = LambertVector(TexelQuad(cubemap, m));
  return ClippedTexelIrradiance(cubemap, m, n,
                                Vec3{float(whole[0]), float(whole[1]), float(whole[2])});
}

double ClippedTexelIrradiance(const Cubemap& cubemap, int m, Vec3 n, Vec3 into) {
  const D3 nd{n.x, n.y, n.z};
  const Polygon clipped = ClipToHemisphere(TexelQuad(cubemap, m), nd);
  if (clipped.n < 3) return 0;
  D3 part = LambertVector(clipped);
  if (Dot(part, D3{into.x, into.y, into.z}) < 0) part = Scale(part, -1);
  return std::max(0.0, Dot(nd, part)) / std::numbers::pi;
}

}  // namespace wavebake
