#include "core/layouts/sample_layout.h"

#include "absl/strings/str_cat.h"
#include "core/layouts/camera_layout.h"

namespace wavebake {

absl::StatusOr<std::pair<int, int>> LayoutGridSize(const Scene& scene, const LayoutSpec& layout) {
  if (layout.kind == LayoutKind::kCamera) {
    if (!scene.camera)
      return absl::InvalidArgumentError(absl::StrCat(
          "layout: ", ToString(layout), " needs the scene's camera and scene '", scene.name,
          "' has none (mesh files carry none: give a .json scene a \"camera\", or use a "
          "hilbert or grid layout)"));
    return std::pair{layout.width, layout.height};
  }
  if (layout.kind == LayoutKind::kHilbert) {
    int64_t vertices = 0;
    for (const Mesh& m : scene.meshes) vertices += static_cast<int64_t>(m.positions.size());
    const int64_t cells = int64_t{layout.width} * layout.height;
    if (vertices > cells)
      return absl::InvalidArgumentError(
          absl::StrCat("layout: ", ToString(layout), ": scene '", scene.name, "' has ", vertices,
                       " vertices, more than the ", cells, " cells; use a larger grid"));
    return std::pair{layout.width, layout.height};
  }
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
