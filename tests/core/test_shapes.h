#pragma once
// Small scenes built in test code: a square plane, a disk as a triangle fan,
// a single triangle. Triangles are counter-clockwise seen from `normal`.
// BuildOrDie makes their ray caster.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/scene.h"
#include "core/transport/ray_caster.h"
#include "core/util/vec3.h"

namespace wavebake::test_shapes {

// Two unit tangents completing the unit normal n to a right-handed frame.
inline std::pair<Vec3, Vec3> Tangents(Vec3 n) {
  const Vec3 helper = std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 u = Normalize(Cross(helper, n));
  return {u, Cross(n, u)};
}

inline Mesh Quad(Vec3 center, Vec3 normal, float half_size, std::string name = "quad") {
  const auto [u, v] = Tangents(Normalize(normal));
  Mesh m;
  m.name = std::move(name);
  m.positions = {center - u * half_size - v * half_size, center + u * half_size - v * half_size,
                 center + u * half_size + v * half_size, center - u * half_size + v * half_size};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Regular `segments`-gon inscribed in the circle of `radius` (vertices on it).
inline Mesh Disk(Vec3 center, Vec3 normal, float radius, int segments) {
  const auto [u, v] = Tangents(Normalize(normal));
  Mesh m;
  m.name = "disk";
  m.positions.push_back(center);
  for (int i = 0; i < segments; ++i) {
    const double a = 2 * std::numbers::pi * i / segments;
    m.positions.push_back(center + u * static_cast<float>(radius * std::cos(a)) +
                          v * static_cast<float>(radius * std::sin(a)));
  }
  for (int i = 0; i < segments; ++i) {
    m.triangles.push_back(
        {0, static_cast<uint32_t>(1 + i), static_cast<uint32_t>(1 + (i + 1) % segments)});
  }
  return m;
}

inline Mesh Triangle(Vec3 a, Vec3 b, Vec3 c, std::string name = "triangle") {
  Mesh m;
  m.name = std::move(name);
  m.positions = {a, b, c};
  m.triangles = {{0, 1, 2}};
  return m;
}

inline Scene SceneOf(std::vector<Mesh> meshes) {
  Scene s;
  s.name = "test";
  s.meshes = std::move(meshes);
  return s;
}

inline RayCaster BuildOrDie(const Scene& scene) {
  absl::StatusOr<RayCaster> caster = RayCaster::Build(scene);
  EXPECT_TRUE(caster.ok()) << caster.status();
  return *std::move(caster);
}

}  // namespace wavebake::test_shapes
