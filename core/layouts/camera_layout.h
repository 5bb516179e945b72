#pragma once
// The `camera` spatial layout (DESIGN.md §1 "Spatial layout"): one sample per
// pixel of the scene's pinhole camera, at the first surface the pixel sees.
#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"
#include "core/transport/ray_caster.h"

namespace wavebake {

// Primary ray through each pixel centre; a hit becomes a sample (position,
// normal turned to face the camera, albedo of the hit mesh), a miss is masked
// (−1 in grid). Sample ids follow row-major pixel order with pixel row 0 the
// TOP of the image. width and height must be powers of two.
absl::StatusOr<SampleSet> CameraLayout(const Scene& scene, const RayCaster& caster, int width,
                                       int height);

}  // namespace wavebake
