#include "core/scene/scene_diff.h"

#include <map>

#include "core/scene/scene_hash.h"

namespace wavebake {
namespace {

bool SameCamera(const std::optional<Camera>& a, const std::optional<Camera>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->eye == b->eye && a->target == b->target && a->up == b->up &&
         a->fov_y_degrees == b->fov_y_degrees;
}

}  // namespace

std::string MeshGeometryHash(const Mesh& mesh) {
  // SceneHash of the mesh alone with a fixed albedo and no camera: the same
  // canonical serialization, minus what rows do not see.
  Scene one;
  one.meshes.push_back(mesh);
  one.meshes.back().albedo = {0, 0, 0};
  one.meshes.back().uv_channels.clear();
  return SceneHash(one);
}

SceneDiff DiffScenes(const Scene& old_scene, const Scene& new_scene) {
  SceneDiff diff;
  // (name, geometry) -> the old meshes of that key not yet paired, in order.
  std::map<std::pair<std::string, std::string>, std::vector<int>> unpaired;
  for (int i = static_cast<int>(old_scene.meshes.size()) - 1; i >= 0; --i) {
    const Mesh& m = old_scene.meshes[i];
    unpaired[{m.name, MeshGeometryHash(m)}].push_back(i);  // reversed: back() is the first
  }
  std::vector<bool> old_paired(old_scene.meshes.size(), false);
  for (int j = 0; j < static_cast<int>(new_scene.meshes.size()); ++j) {
    const Mesh& m = new_scene.meshes[j];
    auto it = unpaired.find({m.name, MeshGeometryHash(m)});
    if (it == unpaired.end() || it->second.empty()) {
      diff.added.push_back(j);
      continue;
    }
    const int i = it->second.back();
    it->second.pop_back();
    old_paired[i] = true;
    diff.unchanged.emplace_back(i, j);
    if (!(old_scene.meshes[i].albedo == m.albedo)) diff.albedo_changed.push_back(j);
  }
  for (int i = 0; i < static_cast<int>(old_scene.meshes.size()); ++i)
    if (!old_paired[i]) diff.removed.push_back(i);
  diff.camera_changed = !SameCamera(old_scene.camera, new_scene.camera);
  return diff;
}

Scene ChangedGeometry(const Scene& old_scene, const Scene& new_scene, const SceneDiff& diff) {
  Scene changed;
  changed.name = new_scene.name + " (changed geometry)";
  for (int i : diff.removed) changed.meshes.push_back(old_scene.meshes[i]);
  for (int j : diff.added) changed.meshes.push_back(new_scene.meshes[j]);
  return changed;
}

Scene RemovedGeometry(const Scene& old_scene, const SceneDiff& diff) {
  Scene s;
  s.name = old_scene.name + " (removed geometry)";
  for (int i : diff.removed) s.meshes.push_back(old_scene.meshes[i]);
  return s;
}

Scene AddedGeometry(const Scene& new_scene, const SceneDiff& diff) {
  Scene s;
  s.name = new_scene.name + " (added geometry)";
  for (int j : diff.added) s.meshes.push_back(new_scene.meshes[j]);
  return s;
}

Scene UnchangedGeometry(const Scene& new_scene, const SceneDiff& diff) {
  Scene kept;
  kept.name = new_scene.name + " (unchanged geometry)";
  for (const auto& [i, j] : diff.unchanged) kept.meshes.push_back(new_scene.meshes[j]);
  return kept;
}

}  // namespace wavebake
