#pragma once
// RayCaster's private state, shared by ray_caster.cc (building) and
// ray_caster_query.cc (queries). Not part of the public API.
#include <array>
#include <cstdint>
#include <vector>

#include "core/transport/embree_handles.h"
#include "core/transport/ray_caster.h"

namespace wavebake {

// One mesh as Embree sees it. Embree shares (does not copy) these buffers, so
// they live exactly as long as the scene; `positions` carries one padding
// element because Embree reads vertex buffers with 16-byte loads.
struct RayCasterMesh {
  std::vector<Vec3> positions;  // size = vertex count + 1 (padding)
  std::vector<Vec3> normals;    // per vertex, or empty: use the geometric normal
  std::vector<std::array<uint32_t, 3>> triangles;
  uint32_t first_vertex = 0;  // global id of vertex 0 (meshes in scene order)
};

struct RayCaster::State {
  // Declaration order = reverse destruction order: the scene is released
  // before the buffers it shares and before its device.
  embree::Device device;
  std::vector<RayCasterMesh> meshes;
  embree::SceneHandle scene;
  Bounds bounds;
  uint32_t vertex_count = 0;
};

}  // namespace wavebake
