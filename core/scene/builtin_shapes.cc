#include "core/scene/builtin_shapes.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace wavebake {
namespace {

constexpr float kTwoPi = 2 * std::numbers::pi_v<float>;

uint32_t AddVertex(Mesh& mesh, SurfacePoint p) {
  mesh.positions.push_back(p.position);
  mesh.normals.push_back(p.normal);
  return static_cast<uint32_t>(mesh.positions.size() - 1);
}

Vec3 Abs(Vec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }

}  // namespace

uint32_t AppendPatch(Mesh& mesh, int nu, int nv, bool wrap_u, const PatchFn& f) {
  const auto first = static_cast<uint32_t>(mesh.positions.size());
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) AddVertex(mesh, f(i, j));
  auto id = [&](int i, int j) { return first + static_cast<uint32_t>(j * nu + i % nu); };
  const int quads_u = wrap_u ? nu : nu - 1;
  for (int j = 0; j + 1 < nv; ++j) {
    for (int i = 0; i < quads_u; ++i) {
      // (i,j) → (i,j+1) → (i+1,j) turns from ∂j to ∂i: normal ∂j × ∂i.
      mesh.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j)});
      mesh.triangles.push_back({id(i + 1, j), id(i, j + 1), id(i + 1, j + 1)});
    }
  }
  return first;
}

void AppendFan(Mesh& mesh, SurfacePoint centre, const std::vector<uint32_t>& ring) {
  const uint32_t c = AddVertex(mesh, centre);
  const size_t n = ring.size();
  // The loop's direction is the caller's; flip the winding if the first
  // triangle would face away from the centre normal.
  const Vec3 a = mesh.positions[ring[0]] - centre.position;
  const Vec3 b = mesh.positions[ring[1 % n]] - centre.position;
  const bool flip = Dot(Cross(a, b), centre.normal) < 0;
  for (size_t k = 0; k < n; ++k) {
    uint32_t p = ring[k], q = ring[(k + 1) % n];
    if (flip) std::swap(p, q);
    mesh.triangles.push_back({c, p, q});
  }
}

std::vector<uint32_t> AppendCircle(Mesh& mesh, Vec3 centre, float radius, int segments,
                                   Vec3 normal) {
  std::vector<uint32_t> ids;
  for (int k = 0; k < segments; ++k) {
    const float t = kTwoPi * static_cast<float>(k) / static_cast<float>(segments);
    ids.push_back(
        AddVertex(mesh, {centre + Vec3{radius * std::cos(t), 0, radius * std::sin(t)}, normal}));
  }
  return ids;
}

Mesh MakeHeightField(std::string name, int n, float x0, float z0, float spacing,
                     const std::function<float(float x, float z)>& height) {
  Mesh mesh;
  mesh.name = std::move(name);
  mesh.grid_width = mesh.grid_height = n;
  // Central differences a hundredth of a cell wide: the normal of the smooth
  // surface, not of the tessellation.
  const float d = spacing * 0.01f;
  AppendPatch(mesh, n, n, false, [&](int i, int j) {
    const float x = x0 + static_cast<float>(i) * spacing;
    const float z = z0 + static_cast<float>(j) * spacing;
    const float dhdx = (height(x + d, z) - height(x - d, z)) / (2 * d);
    const float dhdz = (height(x, z + d) - height(x, z - d)) / (2 * d);
    return SurfacePoint{{x, height(x, z), z}, Normalize({-dhdx, 1, -dhdz})};
  });
  return mesh;
}

void AppendCylinder(Mesh& mesh, Vec3 base, float radius, float height, int segments, int rows) {
  AppendPatch(mesh, segments, rows, true, [&](int i, int j) {
    const float t = kTwoPi * static_cast<float>(i) / static_cast<float>(segments);
    const Vec3 radial{std::cos(t), 0, std::sin(t)};
    const float y = height * static_cast<float>(j) / static_cast<float>(rows - 1);
    return SurfacePoint{base + radial * radius + Vec3{0, y, 0}, radial};
  });
  // The cap gets its own rim vertices: its normal is +Y, not radial.
  const Vec3 top = base + Vec3{0, height, 0};
  AppendFan(mesh, {top, {0, 1, 0}}, AppendCircle(mesh, top, radius, segments, {0, 1, 0}));
}

void AppendOpenBox(Mesh& mesh, Vec3 min_corner, Vec3 max_corner, int n) {
  const Vec3 centre = (min_corner + max_corner) * 0.5f;
  const Vec3 half = (max_corner - min_corner) * 0.5f;
  const Vec3 faces[] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}, {0, 1, 0}};
  for (const Vec3 normal : faces) {
    // Patch axes with V × U = normal, so AppendPatch's winding faces outward.
    const Vec3 v = normal.y != 0 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 u = Cross(normal, v);
    const Vec3 face_centre = centre + normal * Dot(Abs(normal), half);
    const Vec3 u_half = u * Dot(Abs(u), half), v_half = v * Dot(Abs(v), half);
    AppendPatch(mesh, n, n, false, [&](int i, int j) {
      const float s = 2 * static_cast<float>(i) / static_cast<float>(n - 1) - 1;
      const float t = 2 * static_cast<float>(j) / static_cast<float>(n - 1) - 1;
      return SurfacePoint{face_centre + u_half * s + v_half * t, normal};
    });
  }
}

void AppendSphere(Mesh& mesh, Vec3 centre, float radius, int segments, int rings) {
  // Rings strictly between the poles; the poles are fans, because a patch row
  // collapsed onto a pole would be all zero-area triangles.
  const uint32_t first = AppendPatch(mesh, segments, rings, true, [&](int i, int j) {
    const float theta = kTwoPi * static_cast<float>(i) / static_cast<float>(segments);
    const float phi =
        std::numbers::pi_v<float> * static_cast<float>(j + 1) / static_cast<float>(rings + 1);
    const Vec3 n{std::sin(phi) * std::cos(theta), -std::cos(phi), std::sin(phi) * std::sin(theta)};
    return SurfacePoint{centre + n * radius, n};
  });
  auto ring_ids = [&](int j) {
    std::vector<uint32_t> ids;
    for (int i = 0; i < segments; ++i)
      ids.push_back(first + static_cast<uint32_t>(j * segments + i));
    return ids;
  };
  AppendFan(mesh, {centre - Vec3{0, radius, 0}, {0, -1, 0}}, ring_ids(0));
  AppendFan(mesh, {centre + Vec3{0, radius, 0}, {0, 1, 0}}, ring_ids(rings - 1));
}

}  // namespace wavebake
