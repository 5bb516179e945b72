#pragma once
// The one gate every scene passes before a bake (loaded, built-in or
// uploaded): reject what cannot be baked, repair what can be repaired and
// say so. Errors name the mesh and the vertex or triangle.
#include <limits>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "core/scene/scene.h"

namespace wavebake {

// What CheckAndRepairScene changed. The caller decides how to warn.
struct SceneReport {
  int dropped_triangles = 0;          // zero area or a repeated vertex index
  int computed_normals = 0;           // vertices whose normal was missing, zero or not finite
  int isolated_vertices = 0;          // in no triangle: their normal falls back to +Y
  std::vector<std::string> warnings;  // one line per repaired mesh, naming it
};

// Errors (InvalidArgument): no meshes; a mesh without vertices or triangles
// (also after dropping degenerate ones); a vertex that is NaN/Inf; a vertex
// index out of range; normals or grid dims that disagree with the vertex
// count; an albedo outside [0, 1]; a camera with NaN, eye == target or a
// field of view outside (0, 180). Repairs: drops degenerate triangles,
// computes area-weighted smooth normals where a mesh has none (or a bad one),
// normalizes all normals. `report` may be null.
absl::Status CheckAndRepairScene(Scene& scene, SceneReport* report);

struct Bounds3 {
  Vec3 lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
          std::numeric_limits<float>::infinity()};
  Vec3 hi = -lo;

  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  Vec3 centre() const { return (lo + hi) * 0.5f; }
  Vec3 extent() const { return hi - lo; }
  float diagonal() const { return empty() ? 0 : Length(extent()); }
};

// Axis-aligned box of every vertex of every mesh (empty for no vertices).
Bounds3 SceneBounds(const Scene& scene);

}  // namespace wavebake
