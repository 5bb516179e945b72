#include "core/scene/scene_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace wavebake {
namespace {

using ::testing::HasSubstr;

// Unit square in the z = 0 plane, wound counter-clockwise seen from +Z.
Mesh Square(std::string name = "square") {
  Mesh m;
  m.name = std::move(name);
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

Scene One(Mesh m) { return Scene{.name = "test", .meshes = {std::move(m)}, .camera = {}}; }

absl::Status Check(Scene& s) { return CheckAndRepairScene(s, nullptr); }

TEST(SceneCheck, NoMeshesIsAnError) {
  Scene s{.name = "nothing", .meshes = {}, .camera = {}};
  const absl::Status st = Check(s);
  EXPECT_EQ(st.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(st.message(), HasSubstr("no meshes"));
}

TEST(SceneCheck, EmptyMeshIsAnErrorNamingIt) {
  Mesh empty;
  empty.name = "hollow";
  Scene s{.name = "t", .meshes = {Square(), empty}, .camera = {}};
  EXPECT_THAT(Check(s).message(), HasSubstr("hollow"));
  Mesh no_faces = Square("faceless");
  no_faces.triangles.clear();
  Scene t = One(no_faces);
  EXPECT_THAT(Check(t).message(), HasSubstr("faceless"));
}

TEST(SceneCheck, NonFiniteVertexIsAnErrorNamingMeshAndIndex) {
  for (float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    Mesh m = Square("bent");
    m.positions[2].y = bad;
    Scene s = One(m);
    const absl::Status st = Check(s);
    EXPECT_EQ(st.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(st.message(), HasSubstr("bent"));
    EXPECT_THAT(st.message(), HasSubstr("vertex 2"));
  }
}

TEST(SceneCheck, IndexOutOfRangeIsAnError) {
  Mesh m = Square("torn");
  m.triangles.push_back({0, 2, 7});
  Scene s = One(m);
  const absl::Status st = Check(s);
  EXPECT_THAT(st.message(), HasSubstr("torn"));
  EXPECT_THAT(st.message(), HasSubstr("triangle 2"));
  EXPECT_THAT(st.message(), HasSubstr("out of range"));
}

TEST(SceneCheck, DegenerateTrianglesAreDroppedAndCounted) {
  Mesh m = Square();
  m.positions.push_back({2, 0, 0});  // collinear with vertices 0 and 1
  m.triangles.push_back({0, 1, 4});  // zero area
  m.triangles.push_back({2, 2, 3});  // repeated index
  m.triangles.push_back({3, 0, 0});
  Scene s = One(m);
  SceneReport report;
  ASSERT_TRUE(CheckAndRepairScene(s, &report).ok());
  EXPECT_EQ(report.dropped_triangles, 3);
  EXPECT_EQ(s.meshes[0].triangles.size(), 2u);
  ASSERT_EQ(report.warnings.size(), 2u);  // dropped; vertex 4 now isolated
  EXPECT_THAT(report.warnings[0], HasSubstr("square"));
  EXPECT_EQ(report.isolated_vertices, 1);
  EXPECT_EQ(s.meshes[0].normals[4], (Vec3{0, 1, 0}));
}

TEST(SceneCheck, ASliverWithAreaIsKept) {
  Mesh m = Square();
  m.positions.push_back({0.5f, 1e-4f, 0});
  m.triangles.push_back({0, 1, 4});
  Scene s = One(m);
  SceneReport report;
  ASSERT_TRUE(CheckAndRepairScene(s, &report).ok());
  EXPECT_EQ(report.dropped_triangles, 0);
}

TEST(SceneCheck, OnlyDegenerateTrianglesIsAnError) {
  Mesh m = Square("flat");
  m.triangles = {{0, 0, 1}};
  Scene s = One(m);
  EXPECT_THAT(Check(s).message(), HasSubstr("flat"));
}

TEST(SceneCheck, MissingNormalsAreAreaWeightedFaceNormals) {
  // An "L" of two faces meeting at the edge x = 0 ... z-axis: a 1×1 face in
  // the floor (normal +Y) and a 3×1 face in the wall x = 0 (normal +X).
  Mesh m;
  m.name = "corner";
  m.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, {0, 3, 0}, {0, 3, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 4, 5}, {0, 5, 1}};
  Scene s = One(m);
  SceneReport report;
  ASSERT_TRUE(CheckAndRepairScene(s, &report).ok());
  EXPECT_EQ(report.computed_normals, 6);
  const auto& n = s.meshes[0].normals;
  // Vertex 2 only touches the floor; vertex 4 only the wall.
  EXPECT_NEAR(Length(n[2] - Vec3{0, 1, 0}), 0, 1e-6);
  EXPECT_NEAR(Length(n[4] - Vec3{1, 0, 0}), 0, 1e-6);
  // Vertex 1 touches floor triangle (area 1/2) and wall triangle (area 3/2):
  // normal ∝ 0.5·(+Y) + 1.5·(+X).
  EXPECT_NEAR(Length(n[1] - Normalize({1.5f, 0.5f, 0})), 0, 1e-6);
}

TEST(SceneCheck, GivenNormalsAreNormalizedAndBadOnesReplaced) {
  Mesh m = Square();
  m.normals = {{0, 0, 2}, {0, 0, 0.5f}, {0, 0, 0}, {std::nanf(""), 0, 1}};
  Scene s = One(m);
  SceneReport report;
  ASSERT_TRUE(CheckAndRepairScene(s, &report).ok());
  EXPECT_EQ(report.computed_normals, 2);
  for (Vec3 n : s.meshes[0].normals) EXPECT_NEAR(Length(n - Vec3{0, 0, 1}), 0, 1e-6);
}

TEST(SceneCheck, InconsistentFieldsAreErrorsNamingTheMesh) {
  Mesh normals = Square("short");
  normals.normals = {{0, 0, 1}};
  Mesh grid = Square("skewgrid");
  grid.grid_width = 3;
  grid.grid_height = 2;
  Mesh albedo = Square("glowing");
  albedo.albedo = {1.5f, 0, 0};
  for (const Mesh& m : {normals, grid, albedo}) {
    Scene s = One(m);
    const absl::Status st = Check(s);
    EXPECT_EQ(st.code(), absl::StatusCode::kInvalidArgument) << m.name;
    EXPECT_THAT(st.message(), HasSubstr(m.name));
  }
  Mesh ok_grid = Square("twobytwo");
  ok_grid.grid_width = ok_grid.grid_height = 2;
  Scene s = One(ok_grid);
  EXPECT_TRUE(Check(s).ok());
}

TEST(SceneCheck, BadCameraIsAnErrorNamingTheField) {
  Scene s = One(Square());
  s.camera = Camera{.eye = {1, 1, 1}, .target = {1, 1, 1}};
  EXPECT_THAT(Check(s).message(), HasSubstr("camera"));
  s.camera = Camera{.fov_y_degrees = 180};
  EXPECT_THAT(Check(s).message(), HasSubstr("camera.fov_y_degrees"));
  s.camera = Camera{.eye = {0, 5, 0}, .target = {0, 0, 0}, .up = {0, 1, 0}};
  EXPECT_THAT(Check(s).message(), HasSubstr("camera.up"));
  s.camera = Camera{};
  EXPECT_TRUE(Check(s).ok());
}

TEST(SceneCheck, BoundsCoverEveryMesh) {
  Mesh a = Square("a"), b = Square("b");
  for (Vec3& p : b.positions) p = p + Vec3{-3, 2, 5};
  const Scene s{.name = "two", .meshes = {a, b}, .camera = {}};
  const Bounds3 box = SceneBounds(s);
  EXPECT_EQ(box.lo, (Vec3{-3, 0, 0}));
  EXPECT_EQ(box.hi, (Vec3{1, 3, 5}));
  EXPECT_FLOAT_EQ(box.diagonal(), std::sqrt(16.0f + 9 + 25));
  EXPECT_TRUE(SceneBounds(Scene{}).empty());
}

}  // namespace
}  // namespace wavebake
