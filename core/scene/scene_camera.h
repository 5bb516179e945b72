#pragma once
// A default view for scenes that bring no camera (mesh files): the `camera`
// layout needs one, and a framing guess beats failing.
#include "core/scene/scene.h"
#include "core/scene/scene_check.h"

namespace wavebake {

// Looks at the centre of `box` from the front (+Z) and a little above, far
// enough that the box's bounding sphere fits in the vertical field of view
// (and the horizontal one for aspect ≥ 1). Y up.
Camera FramingCamera(const Bounds3& box, float fov_y_degrees = 45);

}  // namespace wavebake
