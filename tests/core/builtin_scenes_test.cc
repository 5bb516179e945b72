#include "core/scene/builtin_scenes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/scene/scene_check.h"
#include "tests/core/scene_testing.h"

namespace wavebake {
namespace {

using namespace builtin;
using testing_util::MeshArea;
using testing_util::TriangleArea;

const Mesh* Find(const Scene& s, const std::string& name) {
  for (const Mesh& m : s.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

Scene Make(const std::string& name) {
  absl::StatusOr<Scene> s = MakeBuiltinScene(name);
  EXPECT_TRUE(s.ok()) << s.status();
  return s.ok() ? *std::move(s) : Scene{};
}

class EveryBuiltin : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryBuiltin, IsCleanHasCameraAndGroundGridFirst) {
  Scene s = Make(GetParam());
  EXPECT_EQ(s.name, GetParam());
  SceneReport report;
  ASSERT_TRUE(CheckAndRepairScene(s, &report).ok());
  EXPECT_EQ(report.dropped_triangles, 0);
  EXPECT_EQ(report.computed_normals, 0) << "built-ins carry exact normals";
  EXPECT_EQ(report.isolated_vertices, 0);
  ASSERT_TRUE(s.camera.has_value());
  const Mesh& ground = s.meshes[0];
  EXPECT_EQ(ground.grid_width, 64);
  EXPECT_EQ(ground.grid_height, 64);
  EXPECT_EQ(ground.positions.size(), 64u * 64u);
  // Vertex (i, j) = j*64 + i on the documented lattice.
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const Vec3 p = ground.positions[j * 64 + i];
      EXPECT_FLOAT_EQ(p.x, kGroundMin + i * kGroundSpacing);
      EXPECT_FLOAT_EQ(p.z, kGroundMin + j * kGroundSpacing);
    }
}

TEST_P(EveryBuiltin, AlbedosDifferPerMesh) {
  const Scene s = Make(GetParam());
  for (size_t a = 0; a < s.meshes.size(); ++a)
    for (size_t b = a + 1; b < s.meshes.size(); ++b)
      EXPECT_NE(s.meshes[a].albedo, s.meshes[b].albedo) << s.meshes[a].name << s.meshes[b].name;
}

// Winding and normals agree: the geometric normal of every triangle points
// the way its vertices' normals do (rays leave from the lit side).
TEST_P(EveryBuiltin, TrianglesFaceTheirVertexNormals) {
  const Scene s = Make(GetParam());
  for (const Mesh& m : s.meshes) {
    int bad = 0;
    for (const auto& t : m.triangles) {
      const Vec3 n =
          Cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
      for (uint32_t v : t) bad += Dot(n, m.normals[v]) <= 0;
    }
    EXPECT_EQ(bad, 0) << m.name;
  }
}

// Everything but the ground is inside the default camera's (square) view.
TEST_P(EveryBuiltin, CameraSeesTheObjects) {
  const Scene s = Make(GetParam());
  const Camera& c = *s.camera;
  const Vec3 f = Normalize(c.target - c.eye);
  const Vec3 right = Normalize(Cross(f, c.up)), up = Cross(right, f);
  const float half = std::tan(c.fov_y_degrees * std::numbers::pi_v<float> / 360);
  for (size_t i = 1; i < s.meshes.size(); ++i)
    for (Vec3 p : s.meshes[i].positions) {
      const Vec3 d = p - c.eye;
      const float z = Dot(d, f);
      ASSERT_GT(z, 0) << s.meshes[i].name;
      EXPECT_LT(std::fabs(Dot(d, right)) / z, half) << s.meshes[i].name;
      EXPECT_LT(std::fabs(Dot(d, up)) / z, half) << s.meshes[i].name;
    }
  const Vec3 d = Vec3{0, 0, 0} - c.eye;  // and the ground's centre
  EXPECT_LT(std::fabs(Dot(d, right)) / Dot(d, f), half);
  EXPECT_LT(std::fabs(Dot(d, up)) / Dot(d, f), half);
}

INSTANTIATE_TEST_SUITE_P(Builtins, EveryBuiltin, ::testing::ValuesIn(BuiltinSceneNames()),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

TEST(BuiltinScenes, NamesAreTheDocumentedFive) {
  EXPECT_THAT(BuiltinSceneNames(),
              ::testing::UnorderedElementsAre("furnace", "disk-over-plane", "cylinder-bump",
                                              "cubes-wall", "sphere-plane"));
}

TEST(BuiltinScenes, UnknownNameIsAnErrorNamingIt) {
  absl::StatusOr<Scene> s = MakeBuiltinScene("teapot");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.status().message(), ::testing::HasSubstr("teapot"));
}

TEST(BuiltinScenes, FurnaceIsOneFlatSquareFacingUp) {
  const Scene s = Make("furnace");
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& plane = s.meshes[0];
  const double side = 63.0 * kGroundSpacing;
  EXPECT_NEAR(MeshArea(plane), side * side, 1e-5 * side * side);
  EXPECT_EQ(plane.triangles.size(), 2u * 63 * 63);
  for (size_t v = 0; v < plane.positions.size(); ++v) {
    EXPECT_EQ(plane.positions[v].y, 0);
    EXPECT_EQ(plane.normals[v], (Vec3{0, 1, 0})) << v;
  }
}

TEST(BuiltinScenes, DiskHasThePolygonAreaAndSitsAboveThePlaneCentre) {
  const Scene s = Make("disk-over-plane");
  const Mesh* disk = Find(s, "disk");
  ASSERT_NE(disk, nullptr);
  const double n = kDiskSegments, r = kDiskRadius;
  const double polygon = n / 2 * r * r * std::sin(2 * std::numbers::pi / n);
  EXPECT_NEAR(MeshArea(*disk), polygon, 1e-5 * polygon);
  EXPECT_NEAR(MeshArea(*disk), std::numbers::pi * r * r, 1e-3 * std::numbers::pi * r * r);
  for (size_t v = 0; v < disk->positions.size(); ++v) {
    const Vec3 p = disk->positions[v] - kDiskPlaneCentre;
    EXPECT_FLOAT_EQ(p.y, kDiskHeight);
    EXPECT_LE(std::hypot(p.x, p.z), kDiskRadius * (1 + 1e-6));
    EXPECT_EQ(disk->normals[v], (Vec3{0, -1, 0}));  // facing the plane
  }
  // The plane centre is a ground vertex, so the analytic occlusion applies to a sample.
  const Vec3 centre = s.meshes[0].positions[kGroundCentreIndex * 64 + kGroundCentreIndex];
  EXPECT_EQ(centre, kDiskPlaneCentre);
}

TEST(BuiltinScenes, CylinderStandsOnFlatGroundBesideTheBump) {
  const Scene s = Make("cylinder-bump");
  const Mesh& ground = s.meshes[0];
  const Mesh* cylinder = Find(s, "cylinder");
  ASSERT_NE(cylinder, nullptr);
  float top = 0, lowest = 1e9f;
  for (Vec3 p : cylinder->positions) {
    EXPECT_LE(std::hypot(p.x - kCylinderBase.x, p.z - kCylinderBase.z), kCylinderRadius * 1.0001f);
    top = std::max(top, p.y);
    lowest = std::min(lowest, p.y);
  }
  EXPECT_FLOAT_EQ(top, kCylinderHeight);
  EXPECT_FLOAT_EQ(lowest, 0);
  float peak = 0;
  for (Vec3 p : ground.positions) {
    peak = std::max(peak, p.y);
    // Flat under the cylinder: it does not float or sink.
    if (std::hypot(p.x - kCylinderBase.x, p.z - kCylinderBase.z) < 2 * kCylinderRadius) {
      EXPECT_LT(p.y, 1e-5f);
    }
  }
  // The nearest lattice vertex is within half a cell of the bump's centre.
  const float d = 0.5f * std::numbers::sqrt2_v<float> * kGroundSpacing;
  EXPECT_LE(peak, kBumpHeight);
  EXPECT_GE(peak, kBumpHeight * std::exp(-d * d / (2 * kBumpSigma * kBumpSigma)));
}

TEST(BuiltinScenes, CubesStandOnTheGroundFarFromTheWall) {
  const Scene s = Make("cubes-wall");
  const Mesh* cubes = Find(s, "cubes");
  const Mesh* wall = Find(s, "wall");
  ASSERT_NE(cubes, nullptr);
  ASSERT_NE(wall, nullptr);
  for (Vec3 p : wall->positions) EXPECT_EQ(p.z, kGroundMin);
  float lowest = 1e9f, nearest_wall = 1e9f;
  for (Vec3 p : cubes->positions) {
    lowest = std::min(lowest, p.y);
    nearest_wall = std::min(nearest_wall, p.z - kGroundMin);
  }
  EXPECT_FLOAT_EQ(lowest, 0);
  EXPECT_GT(nearest_wall, 2 * kCubeSize);
  // Nine open boxes: five faces of side kCubeSize each.
  EXPECT_NEAR(MeshArea(*cubes), 9 * 5 * kCubeSize * kCubeSize, 1e-4);
  EXPECT_NEAR(MeshArea(*wall), kWallHeight * 63 * kGroundSpacing, 1e-4);
}

TEST(BuiltinScenes, SphereRestsOnTheGroundAndIsClosed) {
  const Scene s = Make("sphere-plane");
  const Mesh* sphere = Find(s, "sphere");
  ASSERT_NE(sphere, nullptr);
  float lowest = 1e9f;
  for (Vec3 p : sphere->positions) {
    EXPECT_NEAR(Length(p - kSphereCentre), kSphereRadius, 1e-5);
    lowest = std::min(lowest, p.y);
  }
  EXPECT_NEAR(lowest, 0, 1e-6);
  // Divergence theorem: the signed volume of a closed, outward-wound mesh is
  // positive and close to the sphere's (inscribed polyhedron: slightly less).
  double volume = 0;
  for (const auto& t : sphere->triangles) {
    const Vec3 a = sphere->positions[t[0]] - kSphereCentre,
               b = sphere->positions[t[1]] - kSphereCentre,
               c = sphere->positions[t[2]] - kSphereCentre;
    volume += Dot(a, Cross(b, c)) / 6.0;
  }
  const double exact = 4.0 / 3 * std::numbers::pi * std::pow(kSphereRadius, 3);
  EXPECT_LT(volume, exact);
  EXPECT_GT(volume, 0.98 * exact);
}

}  // namespace
}  // namespace wavebake
