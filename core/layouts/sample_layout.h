#pragma once
// One entry point from a layout spec to the samples of a scene (DESIGN.md §1
// "Spatial layout"), and the grid size alone for planners that must not trace.
#include <utility>

#include "absl/status/statusor.h"
#include "core/layouts/layout.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"
#include "core/transport/ray_caster.h"

namespace wavebake {

// W×H of the layout's grid: from the spec for camera/hilbert, from the first
// grid mesh for grid. No ray is traced, but the layout must fit the scene, so
// a planner refuses a job that every BAKE_TILE would fail (INVALID_ARGUMENT
// naming `layout`): camera needs the scene's camera, grid a regular-grid
// mesh, hilbert at least as many cells as the scene has vertices.
absl::StatusOr<std::pair<int, int>> LayoutGridSize(const Scene& scene, const LayoutSpec& layout);

absl::StatusOr<SampleSet> MakeSampleSet(const Scene& scene, const RayCaster& caster,
                                        const LayoutSpec& layout);

}  // namespace wavebake
