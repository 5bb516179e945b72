#include "core/sample_layout.h"

#include "core/camera_layout.h"

namespace wavebake {

absl::StatusOr<std::pair<int, int>> LayoutGridSize(const Scene& scene, const LayoutSpec& layout) {
  if (layout.kind != LayoutKind::kGrid) return std::pair{layout.width, layout.height};
  for (const Mesh& m : scene.meshes)
    if (m.grid_width > 0) return std::pair{m.grid_width, m.grid_height};
  return absl::InvalidArgumentError(
      "layout: grid needs a regular-grid mesh and the scene has none");
}

absl::StatusOr<SampleSet> MakeSampleSet(const Scene& scene, const RayCaster& caster,
                                        const LayoutSpec& layout) {
  switch (layout.kind) {
    case LayoutKind::kCamera:
      return CameraLayout(scene, caster, layout.width, layout.height);
    case LayoutKind::kGrid:
      return GridLayout(scene);
    case LayoutKind::kHilbert:
      return HilbertLayout(scene, layout.width, layout.height);
    case LayoutKind::kUv:
      return UvLayout(scene, layout);
  }
  return absl::InvalidArgumentError("layout: unknown kind");
}

}  // namespace wavebake
