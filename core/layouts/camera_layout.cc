#include "core/layouts/camera_layout.h"

#include <cmath>
#include <numbers>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/scene/pinhole_frame.h"
#include "core/util/power_of_two.h"

namespace wavebake {

absl::StatusOr<SampleSet> CameraLayout(const Scene& scene, const RayCaster& caster, int width,
                                       int height) {
  if (!scene.camera) return absl::InvalidArgumentError("layout camera needs a camera");
  if (!IsPowerOfTwo(width) || !IsPowerOfTwo(height)) {
    return absl::InvalidArgumentError(absl::StrCat("layout camera: ", width, "x", height,
                                                   " is not a power-of-two width x height"));
  }
  absl::StatusOr<PinholeFrame> frame = MakePinholeFrame(*scene.camera, width, height);
  if (!frame.ok()) return frame.status();

  SampleSet set;
  set.width = width;
  set.height = height;
  set.grid.assign(static_cast<size_t>(width) * height, -1);
  for (int py = 0; py < height; ++py) {
    // Pixel row 0 is the top of the image: sy runs from +1 down to −1.
    const float sy = 1 - 2 * (py + 0.5f) / height;
    for (int px = 0; px < width; ++px) {
      const float sx = 2 * (px + 0.5f) / width - 1;
      const Vec3 dir = frame->forward + frame->right * sx + frame->up * sy;
      const std::optional<Hit> hit = caster.FirstHit(scene.camera->eye, dir);
      if (!hit) continue;
      if (hit->mesh >= scene.meshes.size()) {
        return absl::InvalidArgumentError(
            "layout camera: the ray caster was built from another scene");
      }
      set.grid[static_cast<size_t>(py) * width + px] = set.size();
      set.position.push_back(hit->position);
      // The camera sees the side of the surface that faces it (DESIGN.md §1:
      // rays start at x + ε n, so n must point into the visible half-space).
      set.normal.push_back(Dot(hit->normal, dir) > 0 ? -hit->normal : hit->normal);
      set.albedo.push_back(scene.meshes[hit->mesh].albedo);
    }
  }
  return set;
}

}  // namespace wavebake
