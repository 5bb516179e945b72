#include "core/layouts/camera_layout.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/core/test_shapes.h"

namespace wavebake {
namespace {

using test_shapes::SceneOf;
using ::testing::HasSubstr;

// Two wall quads at z = −5 covering exactly y < 0 (the lower half of the
// view): x < 0 is red, x > 0 is blue. Wound so their normals point AWAY from
// the camera, to check the layout turns them around.
Scene LowerHalfWall() {
  auto wall = [](float x0, float x1, Vec3 albedo, std::string name) {
    Mesh m;
    m.name = std::move(name);
    m.positions = {{x0, -20, -5}, {x1, -20, -5}, {x1, 0, -5}, {x0, 0, -5}};
    m.triangles = {{0, 2, 1}, {0, 3, 2}};  // clockwise seen from +z: normal −z
    m.albedo = albedo;
    return m;
  };
  Scene s = SceneOf({wall(-20, 0, {1, 0, 0}, "red"), wall(0, 20, {0, 0, 1}, "blue")});
  s.camera = Camera{.eye = {0, 0, 0}, .target = {0, 0, -1}, .up = {0, 1, 0}, .fov_y_degrees = 60};
  return s;
}

TEST(CameraLayoutTest, WallOverLowerHalfFillsExactlyTheLowerRows) {
  const Scene scene = LowerHalfWall();
  absl::StatusOr<RayCaster> caster = RayCaster::Build(scene);
  ASSERT_TRUE(caster.ok()) << caster.status();
  constexpr int kW = 16, kH = 8;
  absl::StatusOr<SampleSet> set = CameraLayout(scene, *caster, kW, kH);
  ASSERT_TRUE(set.ok()) << set.status();
  EXPECT_EQ(set->width, kW);
  EXPECT_EQ(set->height, kH);
  ASSERT_EQ(set->grid.size(), size_t{kW * kH});
  EXPECT_EQ(set->size(), kW * kH / 2);
  EXPECT_TRUE(set->vertex.empty());  // not a mesh layout
  int next_id = 0;
  for (int py = 0; py < kH; ++py) {
    for (int px = 0; px < kW; ++px) {
      const int id = set->grid[py * kW + px];
      if (py < kH / 2) {  // row 0 is the top of the image: above the horizon, nothing
        EXPECT_EQ(id, -1) << px << "," << py;
        continue;
      }
      ASSERT_EQ(id, next_id++) << "row-major ids, " << px << "," << py;
      const Vec3 p = set->position[id], n = set->normal[id];
      EXPECT_FLOAT_EQ(p.z, -5);
      EXPECT_LT(p.y, 0);
      EXPECT_EQ(p.x < 0, px < kW / 2) << "image x grows to the camera's right (+x)";
      EXPECT_EQ(n, (Vec3{0, 0, 1})) << "normal faces the camera";
      const Vec3 expected_albedo = px < kW / 2 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
      EXPECT_EQ(set->albedo[id], expected_albedo);
    }
  }
}

TEST(CameraLayoutTest, PixelCentresFollowThePinhole) {
  const Scene scene = LowerHalfWall();
  const RayCaster caster = *RayCaster::Build(scene);
  constexpr int kW = 8, kH = 4;
  const SampleSet set = *CameraLayout(scene, caster, kW, kH);
  // Bottom-left pixel centre: (−1 + 1/W, −1 + 1/H) on the image plane at
  // distance 1, scaled by tan(fov/2) and the aspect ratio, projected to z = −5.
  const float half_h = std::tan(30 * std::numbers::pi_v<float> / 180);
  const int id = set.grid[(kH - 1) * kW + 0];
  ASSERT_GE(id, 0);
  EXPECT_NEAR(set.position[id].x, 5 * (-1 + 1.0f / kW) * half_h * kW / kH, 1e-4f);
  EXPECT_NEAR(set.position[id].y, 5 * (-1 + 1.0f / kH) * half_h, 1e-4f);
}

TEST(CameraLayoutTest, RejectsMissingCameraAndBadResolution) {
  Scene scene = LowerHalfWall();
  const RayCaster caster = *RayCaster::Build(scene);
  EXPECT_THAT(CameraLayout(scene, caster, 12, 8).status().message(), HasSubstr("12x8"));
  scene.camera->target = scene.camera->eye;
  EXPECT_THAT(CameraLayout(scene, caster, 8, 8).status().message(), HasSubstr("target equals eye"));
  scene.camera.reset();
  const absl::Status s = CameraLayout(scene, caster, 8, 8).status();
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("layout camera needs a camera"));
}

}  // namespace
}  // namespace wavebake
