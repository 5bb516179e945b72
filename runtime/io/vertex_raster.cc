#include "runtime/io/vertex_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "core/scene/pinhole_frame.h"
#include "core/scene/scene_camera.h"
#include "core/scene/scene_check.h"

namespace wavebake {
namespace {

// A vertex in the image: continuous pixel coordinates (pixel centres at
// i + 0.5, y down) and its depth along the view.
struct Projected {
  double x = 0, y = 0, z = 0;
};

Projected Project(const PinholeFrame& f, Vec3 eye, Vec3 p, int width, int height) {
  const Vec3 d = p - eye;
  const double z = Dot(d, f.forward);
  const double sx = Dot(d, f.right) / (z * Dot(f.right, f.right));
  const double sy = Dot(d, f.up) / (z * Dot(f.up, f.up));
  return {(sx + 1) * 0.5 * width, (1 - sy) * 0.5 * height, z};
}

double Edge(const Projected& a, const Projected& b, double x, double y) {
  return (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
}

}  // namespace

absl::StatusOr<VertexRaster> VertexRaster::Create(const Scene& scene, const Camera& camera,
                                                  int width, int height) {
  if (width < 1 || width > 4096 || height < 1 || height > 4096) {
    return absl::InvalidArgumentError(
        absl::StrCat("picture: ", width, "x", height, " is not within 1..4096 per side"));
  }
  absl::StatusOr<PinholeFrame> frame = MakePinholeFrame(camera, width, height);
  if (!frame.ok()) return frame.status();
  VertexRaster r;
  r.width_ = width;
  r.height_ = height;
  r.pixels_.resize(static_cast<size_t>(width) * height);
  std::vector<double> nearest(r.pixels_.size(), 0);  // 1/z of what each pixel shows; 0 = nothing
  const double near = 1e-6 * std::max(1.0, static_cast<double>(Length(camera.target - camera.eye)));
  uint32_t base = 0;
  for (const Mesh& mesh : scene.meshes) {
    std::vector<Projected> v(mesh.positions.size());
    for (size_t i = 0; i < v.size(); ++i) {
      v[i] = Project(*frame, camera.eye, mesh.positions[i], width, height);
    }
    for (const std::array<uint32_t, 3>& t : mesh.triangles) {
      const Projected &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
      if (a.z <= near || b.z <= near || c.z <= near) continue;  // behind the camera: skipped
      const double area = Edge(a, b, c.x, c.y);
      if (!(std::abs(area) > 1e-12)) continue;
      const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x, b.x, c.x}) - 0.5)));
      const int x1 =
          std::min(width - 1, static_cast<int>(std::floor(std::max({a.x, b.x, c.x}) - 0.5)));
      const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y, b.y, c.y}) - 0.5)));
      const int y1 =
          std::min(height - 1, static_cast<int>(std::floor(std::max({a.y, b.y, c.y}) - 0.5)));
      for (int py = y0; py <= y1; ++py) {
        for (int px = x0; px <= x1; ++px) {
          const double qx = px + 0.5, qy = py + 0.5;
          const double b0 = Edge(b, c, qx, qy) / area, b1 = Edge(c, a, qx, qy) / area;
          const double b2 = 1 - b0 - b1;
          if (b0 < 0 || b1 < 0 || b2 < 0) continue;
          // Perspective-correct: 1/z and attribute/z are affine in the image.
          const double w0 = b0 / a.z, w1 = b1 / b.z, w2 = b2 / c.z, inv_z = w0 + w1 + w2;
          const size_t p = static_cast<size_t>(py) * width + px;
          if (inv_z <= nearest[p]) continue;
          nearest[p] = inv_z;
          r.pixels_[p] = {.vertex = {base + t[0], base + t[1], base + t[2]},
                          .weight = {static_cast<float>(w0 / inv_z), static_cast<float>(w1 / inv_z),
                                     static_cast<float>(w2 / inv_z)},
                          .covered = true};
        }
      }
    }
    base += static_cast<uint32_t>(mesh.positions.size());
  }
  r.vertices_ = static_cast<int>(base);
  return r;
}

int64_t VertexRaster::covered() const {
  return std::count_if(pixels_.begin(), pixels_.end(), [](const Pixel& p) { return p.covered; });
}

void VertexRaster::Shade(std::span<const float> vertex_rgb, std::span<float> out) const {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (size_t p = 0; p < pixels_.size(); ++p) {
    const Pixel& px = pixels_[p];
    for (int c = 0; c < 3; ++c) {
      float sum = px.covered ? 0.0f : nan;
      if (px.covered) {
        for (int k = 0; k < 3; ++k) sum += px.weight[k] * vertex_rgb[3 * px.vertex[k] + c];
      }
      out[3 * p + c] = sum;
    }
  }
}

Camera PictureCamera(const Scene& scene) {
  return scene.camera ? *scene.camera : FramingCamera(SceneBounds(scene));
}

}  // namespace wavebake
