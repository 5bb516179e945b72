#pragma once
// The spherical cavity of the interreflection tests: the lower half of the
// unit sphere, seen from inside, under a uniform environment. Inside a
// sphere the form factor from any surface element to any region of the
// sphere is that region's share of the sphere's area, whatever the element
// (the property behind the integrating sphere). The bowl's opening is the
// upper half, so with L ≡ 1 every point of the bowl receives
//   direct light   T_0·1 = F(x → opening) = f = 1/2,
// and, each bounce being uniform over the bowl by the same property,
//   T_b·1 = a(1 − f) · T_{b−1}·1   ⇒   Σ_{b≤B} T_b·1 = f Σ_{b≤B} (a(1 − f))^b
// (albedo a, ρ(x) factored out of T as DESIGN.md §1 does). Header-only.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "core/scene/scene.h"

namespace wavebake::test_support {

inline constexpr double kBowlOpening = 0.5;  // f

// Σ_{b=0..bounces} T_b·1 for albedo a.
inline double BowlSeries(double a, int bounces) {
  const double r = a * (1 - kBowlOpening);
  double sum = 0, term = kBowlOpening;
  for (int b = 0; b <= bounces; ++b, term *= r) sum += term;
  return sum;
}

// `rings` rings of `segments` vertices from the pole (0, 0, −1) to the rim
// (the equator z = 0), every vertex on the sphere, normals towards the
// centre, triangles counter-clockwise seen from inside.
inline Mesh BowlMesh(int rings, int segments, float albedo) {
  Mesh m;
  m.name = "bowl";
  m.albedo = {albedo, albedo, albedo};
  m.positions.push_back({0, 0, -1});
  for (int k = 1; k <= rings; ++k) {
    const double psi = std::numbers::pi / 2 * k / rings;  // from the pole
    for (int i = 0; i < segments; ++i) {
      const double phi = 2 * std::numbers::pi * i / segments;
      m.positions.push_back({static_cast<float>(std::sin(psi) * std::cos(phi)),
                             static_cast<float>(std::sin(psi) * std::sin(phi)),
                             static_cast<float>(-std::cos(psi))});
    }
  }
  for (const Vec3& p : m.positions) m.normals.push_back(Normalize(Vec3{} - p));
  auto at = [&](int k, int i) {
    return static_cast<uint32_t>(1 + (k - 1) * segments + i % segments);
  };
  for (int i = 0; i < segments; ++i) m.triangles.push_back({0, at(1, i + 1), at(1, i)});
  for (int k = 1; k < rings; ++k) {
    for (int i = 0; i < segments; ++i) {
      m.triangles.push_back({at(k, i), at(k, i + 1), at(k + 1, i + 1)});
      m.triangles.push_back({at(k, i), at(k + 1, i + 1), at(k + 1, i)});
    }
  }
  return m;
}

// The bowl as an OBJ file with its normals and a UV atlas (the orthographic
// view from above: u, v = (x + 1)/2, (y + 1)/2, one chart without overlap),
// and a JSON scene around it with the albedo and a camera looking into it;
// returns the JSON scene's path.
inline std::filesystem::path WriteBowlScene(const std::filesystem::path& dir, int rings,
                                            int segments, float albedo) {
  const Mesh m = BowlMesh(rings, segments, albedo);
  {
    std::ofstream obj(dir / "bowl.obj");
    for (const Vec3& p : m.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const Vec3& n : m.normals) obj << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
    for (const Vec3& p : m.positions) obj << "vt " << (p.x + 1) / 2 << ' ' << (p.y + 1) / 2 << '\n';
    for (const auto& t : m.triangles) {
      obj << 'f';
      for (uint32_t i : t) obj << ' ' << i + 1 << '/' << i + 1 << '/' << i + 1;
      obj << '\n';
    }
  }
  // A camera above the rim looking down into the bowl, for the camera
  // layouts: every pixel of its 50° view sees the bowl's inside.
  std::ofstream(dir / "bowl.json")
      << "{\"meshes\": [{\"file\": \"bowl.obj\", \"albedo\": [" << albedo << ", " << albedo << ", "
      << albedo << "]}], \"camera\": {\"eye\": [0, 0, 0.6], \"target\": [0, 0, -1], "
      << "\"up\": [0, 1, 0], \"fov_y_degrees\": 50}}";
  return dir / "bowl.json";
}

}  // namespace wavebake::test_support
