#pragma once
// What changed between two versions of a scene, for an update bake (a new
// scene rebaked from an old store's work, Boulton §4.5: only what a change
// can reach). Meshes are matched by name and content: a mesh of the same
// name whose geometry (positions, normals, triangles, grid dims — the
// transform is already applied) hashes the same is unchanged, or changed in
// albedo only, which no row of T sees (albedo is factored out, DESIGN.md §1)
// but samples/albedo does. Any other mesh is a geometric change: its old
// placement (removed) and its new one (added) both bound the rows that may
// differ (core/transport/dirty_rows.h).
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace wavebake {

struct SceneDiff {
  // Indices into the new scene's meshes with no unchanged partner, and into
  // the old scene's meshes none in the new one matched: their triangles are
  // the changed geometry (new and old placement).
  std::vector<int> added, removed;
  // New-scene indices of meshes whose geometry matched but whose albedo differs.
  std::vector<int> albedo_changed;
  // Pairs (old index, new index) of meshes matched by name and geometry.
  std::vector<std::pair<int, int>> unchanged;
  // Both have a camera and it moved, or only one has one: a camera layout's
  // samples are other points altogether (a full bake).
  bool camera_changed = false;

  bool geometry_changed() const { return !added.empty() || !removed.empty(); }
  bool any() const { return geometry_changed() || !albedo_changed.empty() || camera_changed; }
};

// Hash of what a mesh contributes to the rows (not its name, not its albedo,
// not its UVs): the key meshes are matched by, 32 hex digits.
std::string MeshGeometryHash(const Mesh& mesh);

// Same-named meshes are paired in order among those of equal geometry, so
// two instances of one file are told apart by where they are.
SceneDiff DiffScenes(const Scene& old_scene, const Scene& new_scene);

// A Scene holding the changed geometry only: the removed meshes of the old
// scene and the added meshes of the new one (empty if nothing moved).
Scene ChangedGeometry(const Scene& old_scene, const Scene& new_scene, const SceneDiff& diff);
// Its two halves: the old placement (removed meshes) and the new (added).
Scene RemovedGeometry(const Scene& old_scene, const SceneDiff& diff);
Scene AddedGeometry(const Scene& new_scene, const SceneDiff& diff);
// The new scene's meshes that the change left alone (the occluders a
// changed ray may still be blocked by).
Scene UnchangedGeometry(const Scene& new_scene, const SceneDiff& diff);

}  // namespace wavebake
