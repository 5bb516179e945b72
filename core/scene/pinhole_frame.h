#pragma once
// The scene camera's pinhole model (core/scene/scene.h Camera), shared by the
// `camera` layout, which traces a ray through each pixel centre, and by
// pictures that project a mesh into the same view (runtime/io/vertex_raster.h).
#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "core/util/vec3.h"

namespace wavebake {

// Orthonormal pinhole frame; `right` and `up` are pre-scaled to the image
// plane at distance 1 so the ray through image point (sx, sy) ∈ [−1, 1]² is
// forward + sx·right + sy·up (sy = +1 at the top row).
struct PinholeFrame {
  Vec3 forward, right, up;
};

// Errors name the camera field: non-finite vectors, a field of view outside
// (0, 180), eye == target or up parallel to the view.
absl::StatusOr<PinholeFrame> MakePinholeFrame(const Camera& camera, int width, int height);

}  // namespace wavebake
