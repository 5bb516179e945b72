#pragma once
// 2D geometry of the `uv` layout's conservative rasterization, in texel
// coordinates (texel (x, y) is the square [x, x+1] × [y, y+1]).
#include <array>

namespace wavebake {

struct P2 {
  double x = 0, y = 0;
};

// Twice the signed area of (a, b, c).
double Cross2(P2 a, P2 b, P2 c);

// Whether the triangle's interior meets the open texel square — a positive
// area of overlap (the separating axis test with strict inequalities, so a
// triangle that only touches a texel's edge or corner does not cover it). A
// triangle of zero area covers nothing.
bool CoversTexel(const std::array<P2, 3>& tri, int x, int y);

// The point of the (closed) triangle nearest to p, as barycentric weights
// (summing to 1) and its squared distance to p. p itself when inside.
struct NearestPoint {
  std::array<double, 3> bary{};
  double distance2 = 0;
};
NearestPoint NearestOnTriangle(const std::array<P2, 3>& tri, P2 p);

// p lies inside the triangle farther than `margin` from each edge line.
bool InsideBy(const std::array<P2, 3>& tri, P2 p, double margin);

}  // namespace wavebake
