// The `grid` layout: a regular-grid mesh is already an image.
#include "absl/strings/str_cat.h"
#include "core/layouts/layout.h"
#include "core/util/power_of_two.h"

namespace wavebake {

absl::StatusOr<SampleSet> GridLayout(const Scene& scene) {
  int32_t first_vertex = 0;  // global id of the grid mesh's vertex 0
  for (const Mesh& m : scene.meshes) {
    if (m.grid_width <= 0 || m.grid_height <= 0) {
      first_vertex += static_cast<int32_t>(m.positions.size());
      continue;
    }
    const int w = m.grid_width, h = m.grid_height;
    if (!IsPowerOfTwoIn(w, 1, 4096) || !IsPowerOfTwoIn(h, 1, 4096))
      return absl::InvalidArgumentError(
          absl::StrCat("layout 'grid': mesh '", m.name, "' is a ", w, "x", h,
                       " grid; the grid layout needs powers of two up to 4096"));
    const size_t n = static_cast<size_t>(w) * h;
    if (m.positions.size() != n || m.normals.size() != n)
      return absl::FailedPreconditionError(
          absl::StrCat("layout 'grid': mesh '", m.name,
                       "' has not been through CheckAndRepairScene (vertex/normal count)"));
    SampleSet s;
    s.width = w;
    s.height = h;
    s.position = m.positions;
    s.normal = m.normals;
    s.albedo.assign(n, m.albedo);
    s.grid.resize(n);
    s.vertex.resize(n);
    for (size_t c = 0; c < n; ++c) {
      s.grid[c] = static_cast<int32_t>(c);  // cell (i, j) = vertex j*W + i = sample
      s.vertex[c] = first_vertex + static_cast<int32_t>(c);
    }
    return s;
  }
  return absl::InvalidArgumentError(
      absl::StrCat("layout 'grid': scene '", scene.name,
                   "' has no regular-grid mesh (grid_width × grid_height)"));
}

}  // namespace wavebake
