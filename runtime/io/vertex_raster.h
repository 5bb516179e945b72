#pragma once
// A picture of per-vertex values on a mesh (DESIGN.md §5: mesh layouts relight
// to vertex colours): the scene's triangles seen through a pinhole camera
// (core/scene/pinhole_frame.h, the `camera` layout's model), z-buffered. The
// geometry is fixed, so the rasterization is done once: each pixel keeps the
// three vertices of the nearest triangle under its centre and their
// perspective-correct barycentric weights, and a frame is then a weighted
// sum per pixel (Gouraud shading of the vertex colours).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"

namespace wavebake {

class VertexRaster {
 public:
  // Vertices are numbered as samples/vertex does: every mesh's in order.
  // Errors: the camera (named by MakePinholeFrame), a size outside 1..4096.
  static absl::StatusOr<VertexRaster> Create(const Scene& scene, const Camera& camera, int width,
                                             int height);
  int width() const { return width_; }
  int height() const { return height_; }
  int vertices() const { return vertices_; }
  // Pixels a triangle covers.
  int64_t covered() const;

  // out[3p + c] = Σ_k w_k · vertex_rgb[3 v_k + c] for pixel p (row 0 at the
  // top); NaN where no triangle is or a contributing vertex is NaN.
  // vertex_rgb: [3 · vertices()], out: [3 · width · height].
  void Shade(std::span<const float> vertex_rgb, std::span<float> out) const;

 private:
  struct Pixel {
    std::array<uint32_t, 3> vertex{};
    std::array<float, 3> weight{};
    bool covered = false;
  };
  VertexRaster() = default;
  int width_ = 0, height_ = 0, vertices_ = 0;
  std::vector<Pixel> pixels_;
};

// The camera of a scene's picture: its own, else core/scene/scene_camera.h's framing.
Camera PictureCamera(const Scene& scene);

}  // namespace wavebake
