// The picture of per-vertex values (runtime/io/vertex_raster.h): perspective-
// correct interpolation reproduces any colour that is an affine function of
// the world position exactly at every covered pixel — checked against the
// point each pixel's ray hits, traced here independently — the nearest
// surface wins, and pixels without a triangle are NaN.
#include "runtime/io/vertex_raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace wavebake {
namespace {

// A square in the plane z = z0 facing +Z, two triangles.
Mesh Square(float half, float z0) {
  Mesh m;
  m.positions = {{-half, -half, z0}, {half, -half, z0}, {half, half, z0}, {-half, half, z0}};
  m.normals.assign(4, Vec3{0, 0, 1});
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// The camera of every test: on the +Z axis, looking at the origin, tilted
// so the interpolation is not merely affine in the image.
Camera TestCamera() { return {.eye = {0.7f, 0.4f, 5}, .target = {0, 0, 0}, .fov_y_degrees = 40}; }

// Where pixel (px, py)'s centre ray meets the plane z = z0, from the same
// pinhole definition as the camera layout (core/layouts/camera_layout.cc).
Vec3 HitOfPixel(const Camera& cam, int px, int py, int w, int h, float z0) {
  const Vec3 f = Normalize(cam.target - cam.eye);
  const Vec3 r = Normalize(Cross(cam.target - cam.eye, cam.up));
  const Vec3 u = Cross(r, f);
  const double half_h = std::tan(cam.fov_y_degrees * std::numbers::pi / 360.0);
  const double sx = (2 * (px + 0.5) / w - 1) * half_h * w / h,
               sy = (1 - 2 * (py + 0.5) / h) * half_h;
  const Vec3 d = f + r * static_cast<float>(sx) + u * static_cast<float>(sy);
  const float t = (z0 - cam.eye.z) / d.z;
  return cam.eye + d * t;
}

TEST(VertexRasterTest, AffineColoursAreReproducedAtEveryCoveredPixel) {
  Scene scene;
  scene.meshes.push_back(Square(1.5f, 0));
  const int w = 64, h = 48;
  absl::StatusOr<VertexRaster> raster = VertexRaster::Create(scene, TestCamera(), w, h);
  ASSERT_TRUE(raster.ok()) << raster.status();
  // colour = (x, y, 2x − y + 3) at each vertex
  std::vector<float> colours;
  for (const Vec3& p : scene.meshes[0].positions) {
    colours.insert(colours.end(), {p.x, p.y, 2 * p.x - p.y + 3});
  }
  std::vector<float> image(3 * w * h);
  raster->Shade(colours, image);
  int covered = 0, background = 0;
  for (int py = 0; py < h; ++py) {
    for (int px = 0; px < w; ++px) {
      const float* c = &image[3 * (py * w + px)];
      const Vec3 hit = HitOfPixel(TestCamera(), px, py, w, h, 0);
      const bool inside = std::abs(hit.x) < 1.5f && std::abs(hit.y) < 1.5f;
      const bool edge =
          std::abs(std::abs(hit.x) - 1.5f) < 0.05f || std::abs(std::abs(hit.y) - 1.5f) < 0.05f;
      if (edge) continue;  // a pixel centre within a hair of the border may go either way
      if (!inside) {
        EXPECT_TRUE(std::isnan(c[0])) << px << "," << py;
        ++background;
        continue;
      }
      ++covered;
      EXPECT_NEAR(c[0], hit.x, 1e-4) << px << "," << py;
      EXPECT_NEAR(c[1], hit.y, 1e-4) << px << "," << py;
      EXPECT_NEAR(c[2], 2 * hit.x - hit.y + 3, 3e-4) << px << "," << py;
    }
  }
  EXPECT_GT(covered, 500);
  EXPECT_GT(background, 200);
  EXPECT_GE(raster->covered(), covered);
  EXPECT_LE(raster->covered(), w * h - background);
}

TEST(VertexRasterTest, TheNearestSurfaceWins) {
  Scene scene;
  scene.meshes.push_back(Square(1.5f, 0));  // far, colour 0
  scene.meshes.push_back(Square(0.5f, 1));  // near, colour 1, in front of the middle
  const int w = 32, h = 32;
  absl::StatusOr<VertexRaster> raster = VertexRaster::Create(scene, TestCamera(), w, h);
  ASSERT_TRUE(raster.ok()) << raster.status();
  ASSERT_EQ(raster->vertices(), 8);
  std::vector<float> colours(3 * 8, 0.0f);
  for (int i = 12; i < 24; ++i) colours[i] = 1;  // the second mesh's vertices
  std::vector<float> image(3 * w * h);
  raster->Shade(colours, image);
  int near = 0, far = 0;
  for (int py = 0; py < h; ++py) {
    for (int px = 0; px < w; ++px) {
      const Vec3 on_near = HitOfPixel(TestCamera(), px, py, w, h, 1);
      const Vec3 on_far = HitOfPixel(TestCamera(), px, py, w, h, 0);
      const float v = image[3 * (py * w + px)];
      if (std::abs(on_near.x) < 0.45f && std::abs(on_near.y) < 0.45f) {
        EXPECT_NEAR(v, 1.0f, 1e-6) << px << "," << py;  // weights sum to 1 in float
        ++near;
      } else if (std::abs(on_far.x) < 1.45f && std::abs(on_far.y) < 1.45f &&
                 (std::abs(on_near.x) > 0.55f || std::abs(on_near.y) > 0.55f)) {
        EXPECT_EQ(v, 0.0f) << px << "," << py;
        ++far;
      }
    }
  }
  EXPECT_GT(near, 20);
  EXPECT_GT(far, 100);
}

TEST(VertexRasterTest, NanVerticesAndBadSizesShowAsNothing) {
  Scene scene;
  scene.meshes.push_back(Square(1.5f, 0));
  EXPECT_FALSE(VertexRaster::Create(scene, TestCamera(), 0, 8).ok());
  Camera bad = TestCamera();
  bad.target = bad.eye;
  EXPECT_FALSE(VertexRaster::Create(scene, bad, 8, 8).ok());
  absl::StatusOr<VertexRaster> raster = VertexRaster::Create(scene, TestCamera(), 16, 16);
  ASSERT_TRUE(raster.ok());
  std::vector<float> colours(12, 1.0f);
  colours[0] = NAN;  // vertex 0, red: every triangle touches it
  std::vector<float> image(3 * 16 * 16);
  raster->Shade(colours, image);
  for (int p = 0; p < 16 * 16; ++p) EXPECT_TRUE(std::isnan(image[3 * p])) << p;
}

}  // namespace
}  // namespace wavebake
