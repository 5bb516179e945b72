#include "core/layouts/uv_raster.h"

#include <algorithm>
#include <cmath>

namespace wavebake {
namespace {

double Dot2(P2 a, P2 b) { return a.x * b.x + a.y * b.y; }

// Projections of the triangle and of the texel square on `axis` overlap in
// more than a point.
bool Overlaps(const std::array<P2, 3>& tri, int x, int y, P2 axis) {
  double tlo = INFINITY, thi = -INFINITY, slo = INFINITY, shi = -INFINITY;
  for (P2 v : tri) {
    const double d = Dot2(v, axis);
    tlo = std::min(tlo, d);
    thi = std::max(thi, d);
  }
  for (P2 c : {P2{double(x), double(y)}, P2{x + 1.0, double(y)}, P2{double(x), y + 1.0},
               P2{x + 1.0, y + 1.0}}) {
    const double d = Dot2(c, axis);
    slo = std::min(slo, d);
    shi = std::max(shi, d);
  }
  return thi > slo && shi > tlo;
}

}  // namespace

double Cross2(P2 a, P2 b, P2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

bool CoversTexel(const std::array<P2, 3>& tri, int x, int y) {
  if (Cross2(tri[0], tri[1], tri[2]) == 0) return false;
  if (!Overlaps(tri, x, y, {1, 0}) || !Overlaps(tri, x, y, {0, 1})) return false;
  for (int e = 0; e < 3; ++e) {
    const P2 a = tri[e], b = tri[(e + 1) % 3];
    if (!Overlaps(tri, x, y, {a.y - b.y, b.x - a.x})) return false;
  }
  return true;
}

NearestPoint NearestOnTriangle(const std::array<P2, 3>& tri, P2 p) {
  const double area = Cross2(tri[0], tri[1], tri[2]);
  // Weight of vertex i is the area of the sub-triangle opposite it.
  const double w0 = Cross2(p, tri[1], tri[2]), w1 = Cross2(tri[0], p, tri[2]),
               w2 = Cross2(tri[0], tri[1], p);
  if (area != 0 && w0 / area >= 0 && w1 / area >= 0 && w2 / area >= 0)
    return {{w0 / area, w1 / area, w2 / area}, 0};
  NearestPoint best{{}, INFINITY};
  for (int e = 0; e < 3; ++e) {  // outside: the nearest point of the nearest edge
    const int i = e, j = (e + 1) % 3;
    const P2 a = tri[i], b = tri[j], ab{b.x - a.x, b.y - a.y};
    const double len2 = Dot2(ab, ab);
    const double t = len2 > 0 ? std::clamp(Dot2({p.x - a.x, p.y - a.y}, ab) / len2, 0.0, 1.0) : 0;
    const P2 q{a.x + t * ab.x, a.y + t * ab.y};
    const double d2 = Dot2({p.x - q.x, p.y - q.y}, {p.x - q.x, p.y - q.y});
    if (d2 < best.distance2) {
      best = {{}, d2};
      best.bary[i] = 1 - t;
      best.bary[j] = t;
    }
  }
  return best;
}

bool InsideBy(const std::array<P2, 3>& tri, P2 p, double margin) {
  const double area = Cross2(tri[0], tri[1], tri[2]);
  if (area == 0) return false;
  for (int e = 0; e < 3; ++e) {
    const P2 a = tri[e], b = tri[(e + 1) % 3];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    // Signed distance of p from edge a→b, positive on the triangle's side.
    if (Cross2(a, b, p) / (area > 0 ? len : -len) <= margin) return false;
  }
  return true;
}

}  // namespace wavebake
