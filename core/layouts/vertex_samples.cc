#include "core/layouts/vertex_samples.h"

namespace wavebake {

int64_t VertexCount(const Scene& scene) {
  int64_t count = 0;
  for (const Mesh& m : scene.meshes) count += static_cast<int64_t>(m.positions.size());
  return count;
}

SampleSet VertexSamples(const Scene& scene) {
  SampleSet s;
  for (const Mesh& m : scene.meshes) {
    s.position.insert(s.position.end(), m.positions.begin(), m.positions.end());
    s.normal.insert(s.normal.end(), m.normals.begin(), m.normals.end());
    s.albedo.insert(s.albedo.end(), m.positions.size(), m.albedo);
  }
  s.normal.resize(s.position.size());  // CheckAndRepairScene gives every mesh its normals
  s.width = s.size();
  s.height = 1;
  for (int32_t v = 0; v < s.size(); ++v) {
    s.grid.push_back(v);
    s.vertex.push_back(v);
  }
  return s;
}

}  // namespace wavebake
