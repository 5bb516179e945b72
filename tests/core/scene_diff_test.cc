// The scene diff of an update bake: meshes matched by name and geometry; a
// moved, added or removed mesh is a geometric change, an albedo edit is not
// one, a moved camera is said.
#include "core/scene/scene_diff.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/scene/builtin_scenes.h"

namespace wavebake {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

Scene Base() { return *MakeBuiltinScene("sphere-plane"); }  // meshes: ground, sphere

void Translate(Mesh& m, Vec3 by) {
  for (Vec3& p : m.positions) p = p + by;
}

TEST(SceneDiff, SameSceneIsUnchanged) {
  const SceneDiff d = DiffScenes(Base(), Base());
  EXPECT_FALSE(d.any());
  EXPECT_THAT(d.unchanged, ElementsAre(std::pair{0, 0}, std::pair{1, 1}));
}

TEST(SceneDiff, MovedMeshIsRemovedAndAdded) {
  Scene moved = Base();
  Translate(moved.meshes[1], {0.25f, 0, 0});
  const SceneDiff d = DiffScenes(Base(), moved);
  EXPECT_TRUE(d.geometry_changed());
  EXPECT_THAT(d.removed, ElementsAre(1));
  EXPECT_THAT(d.added, ElementsAre(1));
  EXPECT_THAT(d.unchanged, ElementsAre(std::pair{0, 0}));
  const Scene changed = ChangedGeometry(Base(), moved, d);
  ASSERT_EQ(changed.meshes.size(), 2u);
  EXPECT_EQ(changed.meshes[0].positions[0], Base().meshes[1].positions[0]);
  EXPECT_EQ(changed.meshes[1].positions[0], moved.meshes[1].positions[0]);
  EXPECT_EQ(UnchangedGeometry(moved, d).meshes.size(), 1u);
}

TEST(SceneDiff, OneVertexNudgedIsAChange) {
  Scene nudged = Base();
  nudged.meshes[0].positions[5].y += 1e-6f;
  EXPECT_THAT(DiffScenes(Base(), nudged).added, ElementsAre(0));
}

TEST(SceneDiff, AlbedoAloneIsNoGeometricChange) {
  Scene painted = Base();
  painted.meshes[1].albedo = {0.1f, 0.2f, 0.3f};
  const SceneDiff d = DiffScenes(Base(), painted);
  EXPECT_FALSE(d.geometry_changed());
  EXPECT_TRUE(d.any());
  EXPECT_THAT(d.albedo_changed, ElementsAre(1));
}

TEST(SceneDiff, AddedAndRemovedMeshes) {
  Scene more = Base();
  more.meshes.push_back(more.meshes[1]);
  more.meshes.back().name = "sphere2";
  Translate(more.meshes.back(), {0, 1, 0});
  SceneDiff d = DiffScenes(Base(), more);
  EXPECT_THAT(d.added, ElementsAre(2));
  EXPECT_THAT(d.removed, IsEmpty());
  d = DiffScenes(more, Base());
  EXPECT_THAT(d.removed, ElementsAre(2));
  EXPECT_THAT(d.added, IsEmpty());
}

TEST(SceneDiff, RenamedMeshIsAChangeEvenWithTheSameGeometry) {
  Scene renamed = Base();
  renamed.meshes[1].name = "ball";
  const SceneDiff d = DiffScenes(Base(), renamed);
  EXPECT_THAT(d.removed, ElementsAre(1));
  EXPECT_THAT(d.added, ElementsAre(1));
}

TEST(SceneDiff, TwoInstancesOfOneMeshAreToldApartByPlacement) {
  Scene two = Base();
  two.meshes.push_back(two.meshes[1]);
  Translate(two.meshes[2], {1, 0, 0});  // same name "sphere", elsewhere
  Scene swapped = two;
  std::swap(swapped.meshes[1], swapped.meshes[2]);  // same content, other order
  SceneDiff d = DiffScenes(two, swapped);
  EXPECT_FALSE(d.geometry_changed());
  EXPECT_THAT(d.unchanged, ElementsAre(std::pair{0, 0}, std::pair{2, 1}, std::pair{1, 2}));
  Scene one_moved = two;
  Translate(one_moved.meshes[2], {0, 0, 1});
  d = DiffScenes(two, one_moved);
  EXPECT_THAT(d.removed, ElementsAre(2));
  EXPECT_THAT(d.added, ElementsAre(2));
}

TEST(SceneDiff, CameraMoveIsSaid) {
  Scene moved = Base();
  moved.camera->eye.x += 0.5f;
  const SceneDiff d = DiffScenes(Base(), moved);
  EXPECT_TRUE(d.camera_changed);
  EXPECT_FALSE(d.geometry_changed());
  Scene none = Base();
  none.camera.reset();
  EXPECT_TRUE(DiffScenes(Base(), none).camera_changed);
}

}  // namespace
}  // namespace wavebake
