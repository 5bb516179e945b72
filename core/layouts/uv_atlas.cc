#include "core/layouts/uv_atlas.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

// Cell (x, y) of Morton index i inside a square: even bits are x, odd bits y.
void MortonDecode(int64_t i, int* x, int* y) {
  *x = *y = 0;
  for (int b = 0; i >> (2 * b); ++b) {
    *x |= static_cast<int>((i >> (2 * b)) & 1) << b;
    *y |= static_cast<int>((i >> (2 * b + 1)) & 1) << b;
  }
}

int64_t Square(int side) { return int64_t{side} * side; }

}  // namespace

UvDomain MeshUvDomain(std::span<const Vec2> uvs) {
  UvDomain d;
  for (Vec2 t : uvs) {
    d.u0 = std::min(d.u0, t.u);
    d.v0 = std::min(d.v0, t.v);
    d.u1 = std::max(d.u1, t.u);
    d.v1 = std::max(d.v1, t.v);
  }
  return d;
}

std::vector<double> MeshAreas(const Scene& scene) {
  std::vector<double> areas;
  for (const Mesh& m : scene.meshes) {
    double a = 0;
    for (const auto& t : m.triangles)
      a += 0.5 * Length(Cross(m.positions[t[1]] - m.positions[t[0]],
                              m.positions[t[2]] - m.positions[t[0]]));
    areas.push_back(a);
  }
  return areas;
}

absl::StatusOr<std::vector<TexelRect>> PackCharts(std::span<const double> surface_areas, int width,
                                                  int height) {
  const size_t n = surface_areas.size();
  if (n == 1) return std::vector<TexelRect>{{0, 0, width, height}};
  const int side_max = std::min(width, height);
  const int64_t texels = int64_t{width} * height;
  if (n == 0 || static_cast<int64_t>(n) > texels)
    return absl::InvalidArgumentError(
        absl::StrCat("layout: ", n, " meshes do not fit a ", width, "x", height, " lightmap"));
  const double total = std::accumulate(surface_areas.begin(), surface_areas.end(), 0.0);
  std::vector<double> share(n);
  std::vector<int> side(n, 1);
  int64_t used = 0;
  for (size_t i = 0; i < n; ++i) {
    share[i] = total > 0 ? surface_areas[i] / total * double(texels) : double(texels) / n;
    while (side[i] < side_max && double(Square(2 * side[i])) <= share[i]) side[i] *= 2;
    used += Square(side[i]);
  }
  // Only reachable by the at-least-1 rule with many tiny meshes: shrink the largest.
  while (used > texels) {
    const size_t big = std::max_element(side.begin(), side.end()) - side.begin();
    used -= Square(side[big]) - Square(side[big] / 2);
    side[big] /= 2;
  }
  for (;;) {  // grow the most under-served mesh while its doubled square fits
    size_t pick = n;
    for (size_t i = 0; i < n; ++i) {
      if (side[i] >= side_max || used + 3 * Square(side[i]) > texels) continue;
      if (pick == n || share[i] / Square(side[i]) > share[pick] / Square(side[pick])) pick = i;
    }
    if (pick == n) break;
    used += 3 * Square(side[pick]);
    side[pick] *= 2;
  }
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return side[a] > side[b]; });
  std::vector<TexelRect> rects(n);
  int64_t cursor = 0;  // in texels along the Z order; a multiple of every later square
  const int64_t block = Square(side_max);
  for (size_t i : order) {
    int x = 0, y = 0;
    MortonDecode(cursor % block, &x, &y);
    const int along = static_cast<int>(cursor / block) * side_max;
    rects[i] = width >= height ? TexelRect{along + x, y, side[i], side[i]}
                               : TexelRect{x, along + y, side[i], side[i]};
    cursor += Square(side[i]);
  }
  return rects;
}

}  // namespace wavebake
