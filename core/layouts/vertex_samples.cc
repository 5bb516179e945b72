#include "core/layouts/vertex_samples.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace wavebake {

int64_t VertexCount(const Scene& scene) {
  int64_t count = 0;
  for (const Mesh& m : scene.meshes) count += static_cast<int64_t>(m.positions.size());
  return count;
}

namespace {

// Per vertex of m: the unit direction from it into its triangles (the mean
// of the directions to their centroids, in the tangent plane) for vertices
// on the mesh's boundary, zero for the others and where the mean vanishes.
std::vector<Vec3> BoundaryInward(const Mesh& m) {
  // Edges as sorted (lower, upper) keys: an edge used once is a boundary.
  std::vector<uint64_t> edges;
  edges.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto [a, b] = std::minmax(t[k], t[(k + 1) % 3]);
      edges.push_back(uint64_t{a} << 32 | b);
    }
  std::sort(edges.begin(), edges.end());
  std::vector<uint8_t> boundary(m.positions.size(), 0);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) boundary[edges[i] >> 32] = boundary[edges[i] & 0xffffffffu] = 1;
    i = j;
  }
  std::vector<Vec3> sum(m.positions.size(), Vec3{});
  for (const auto& t : m.triangles) {
    const Vec3 centroid = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0f;
    for (uint32_t v : t)
      if (boundary[v]) {
        const Vec3 d = centroid - m.positions[v];
        const float len = Length(d);
        if (len > 0) sum[v] = sum[v] + d / len;
      }
  }
  for (size_t v = 0; v < sum.size(); ++v) {
    const Vec3 n = v < m.normals.size() ? m.normals[v] : Vec3{};
    const Vec3 tangent = sum[v] - n * Dot(sum[v], n);
    const float len = Length(tangent);
    sum[v] = len > 1e-6f ? tangent / len : Vec3{};
  }
  return sum;
}

}  // namespace

SampleSet VertexSamples(const Scene& scene, float inset) {
  SampleSet s;
  for (const Mesh& m : scene.meshes) {
    if (inset > 0) {
      const std::vector<Vec3> inward = BoundaryInward(m);
      for (size_t v = 0; v < m.positions.size(); ++v)
        s.position.push_back(m.positions[v] + inward[v] * inset);
    } else {
      s.position.insert(s.position.end(), m.positions.begin(), m.positions.end());
    }
    s.normal.insert(s.normal.end(), m.normals.begin(), m.normals.end());
    s.albedo.insert(s.albedo.end(), m.positions.size(), m.albedo);
  }
  s.normal.resize(s.position.size());  // CheckAndRepairScene gives every mesh its normals
  s.width = s.size();
  s.height = 1;
  for (int32_t v = 0; v < s.size(); ++v) {
    s.grid.push_back(v);
    s.vertex.push_back(v);
  }
  return s;
}

}  // namespace wavebake
