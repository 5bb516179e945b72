#pragma once
// The path tracer's own ray queries (runtime/reference/path_reference.h):
// an Embree 3 scene built from the Scene's meshes here, not the bake's
// RayCaster (core/transport/ray_caster.h), so that the reference shares no
// tracing code with the transport and the bounce gather it checks: its own
// hit points (along the ray to Embree's t) and its own shading normals (the
// vertex normals interpolated by Embree's barycentrics), whose side is the
// surface's front, as a sample's normal is its front.
#include <cstdint>
#include <memory>
#include <optional>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "core/util/vec3.h"

namespace wavebake {

struct PathHit {
  uint32_t mesh = 0;
  Vec3 position, normal;  // normal: the shading normal, unit, on the front side
  bool front = true;      // the ray met the triangle's front face
};

class PathScene {
 public:
  static absl::StatusOr<PathScene> Build(const Scene& scene);
  PathScene(PathScene&&) noexcept;
  PathScene& operator=(PathScene&&) noexcept;
  ~PathScene();

  // The first surface along the unit direction from origin (t > 0), if any.
  std::optional<PathHit> Trace(Vec3 origin, Vec3 dir) const;
  // Whether any surface lies along dir from origin (t > 0).
  bool Blocked(Vec3 origin, Vec3 dir) const;
  // 1e-4 × the scene's bounding-box diagonal: the ray offset off surfaces.
  float Offset() const { return offset_; }

 private:
  struct State;
  explicit PathScene(std::unique_ptr<State> state, float offset);
  std::unique_ptr<State> state_;
  float offset_ = 0;
};

}  // namespace wavebake
