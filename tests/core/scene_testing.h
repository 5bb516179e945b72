#pragma once
// Geometry helpers shared by the scene, layout and loader tests: independent
// of the code under test, so the tests compare against geometry, not itself.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/layouts/samples.h"
#include "core/scene/scene.h"

namespace wavebake::testing_util {

inline double TriangleArea(const Mesh& m, const std::array<uint32_t, 3>& t) {
  const Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
  return 0.5 * static_cast<double>(Length(Cross(b - a, c - a)));
}

inline double MeshArea(const Mesh& m) {
  double sum = 0;
  for (const auto& t : m.triangles) sum += TriangleArea(m, t);
  return sum;
}

// Generalized winding number of a triangle mesh around q: the sum of the
// triangles' signed solid angles over 4π (Van Oosterom–Strackee). ≈1 inside
// a closed outward-wound surface, ≈0 outside, and robust to small holes.
inline double WindingNumber(const Mesh& m, Vec3 q) {
  double sum = 0;
  for (const auto& t : m.triangles) {
    const Vec3 a = m.positions[t[0]] - q, b = m.positions[t[1]] - q, c = m.positions[t[2]] - q;
    const double la = Length(a), lb = Length(b), lc = Length(c);
    const double num = Dot(a, Cross(b, c));
    const double den = la * lb * lc + Dot(a, b) * lc + Dot(a, c) * lb + Dot(b, c) * la;
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * 3.14159265358979323846);
}

// Mean distance between the samples of horizontally adjacent, unmasked cells.
inline double MeanNeighbourDistance(const SampleSet& s, const std::vector<int32_t>& grid) {
  double sum = 0;
  int pairs = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x + 1 < s.width; ++x) {
      const int32_t a = grid[y * s.width + x], b = grid[y * s.width + x + 1];
      if (a < 0 || b < 0) continue;
      sum += Length(s.position[a] - s.position[b]);
      ++pairs;
    }
  return pairs ? sum / pairs : 0;
}

// The same measure with the samples shuffled over the same cells: what a
// layout without spatial coherence would give.
inline double RandomNeighbourDistance(const SampleSet& s) {
  std::vector<int32_t> ids;
  for (int32_t id : s.grid)
    if (id >= 0) ids.push_back(id);
  std::mt19937 rng(12345);
  std::shuffle(ids.begin(), ids.end(), rng);
  std::vector<int32_t> grid = s.grid;
  size_t k = 0;
  for (int32_t& id : grid)
    if (id >= 0) id = ids[k++];
  return MeanNeighbourDistance(s, grid);
}

// Every sample id 0..S-1 in exactly one cell; returns the number of masked cells.
inline int CheckBijection(const SampleSet& s, bool* ok) {
  std::vector<int> seen(s.size(), 0);
  int masked = 0;
  *ok = static_cast<int>(s.grid.size()) == s.cells();
  for (int32_t id : s.grid) {
    if (id == -1) {
      ++masked;
    } else if (id < 0 || id >= s.size() || seen[id]++) {
      *ok = false;
    }
  }
  *ok = *ok && std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; });
  return masked;
}

}  // namespace wavebake::testing_util
