#include "core/scene/scene_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wavebake {

Camera FramingCamera(const Bounds3& box, float fov_y_degrees) {
  const float radius = std::max(0.5f * box.diagonal(), 1e-6f);
  const float half_fov = 0.5f * fov_y_degrees * std::numbers::pi_v<float> / 180;
  // A sphere of radius r fits a cone of half-angle a from distance r / sin a;
  // 5 % margin so silhouettes do not touch the image border.
  const float distance = 1.05f * radius / std::sin(half_fov);
  const Vec3 direction = Normalize({0, 0.5f, 1});
  return Camera{.eye = box.centre() + direction * distance,
                .target = box.centre(),
                .up = {0, 1, 0},
                .fov_y_degrees = fov_y_degrees};
}

}  // namespace wavebake
