#include "core/scene/pinhole_frame.h"

#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"

namespace wavebake {

absl::StatusOr<PinholeFrame> MakePinholeFrame(const Camera& cam, int width, int height) {
  if (!IsFinite(cam.eye) || !IsFinite(cam.target) || !IsFinite(cam.up)) {
    return absl::InvalidArgumentError("layout camera: eye, target and up must be finite");
  }
  if (!(cam.fov_y_degrees > 0 && cam.fov_y_degrees < 180)) {
    return absl::InvalidArgumentError(
        absl::StrCat("layout camera: fov_y_degrees ", cam.fov_y_degrees, " is not in (0, 180)"));
  }
  const Vec3 view = cam.target - cam.eye;
  const Vec3 side = Cross(view, cam.up);
  if (!(Dot(view, view) > 0) || !(Dot(side, side) > 0)) {
    return absl::InvalidArgumentError(
        "layout camera: target equals eye, or up is parallel to the view direction");
  }
  const float half_h = static_cast<float>(std::tan(cam.fov_y_degrees * std::numbers::pi / 360.0));
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  PinholeFrame f;
  f.forward = Normalize(view);
  const Vec3 right = Normalize(side);
  f.right = right * (half_h * aspect);
  f.up = Cross(right, f.forward) * half_h;
  return f;
}

}  // namespace wavebake
