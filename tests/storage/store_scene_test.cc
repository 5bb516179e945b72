// Where a store's scene is found (storage/store/store_scene.h): built-ins as
// named; a file name as given, beside the store, then along
// $WAVEBAKE_SCENE_PATH; a store records names, never directories.
#include "storage/store/store_scene.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>

#include "tests/testing/scratch_dir.h"

namespace wavebake {
namespace {

TEST(StoreSceneTest, RecordsTheNameOnly) {
  EXPECT_EQ(RecordedSceneName("builtin:cubes-wall"), "builtin:cubes-wall");
  EXPECT_EQ(RecordedSceneName("/home/someone/models/ogre.obj"), "ogre.obj");
  EXPECT_EQ(RecordedSceneName("scenes/room.json"), "room.json");
  EXPECT_EQ(RecordedSceneName("tent.ply"), "tent.ply");
}

TEST(StoreSceneTest, FindsTheSceneBesideTheStoreThenAlongThePath) {
  test_support::ScratchDir dir("store_scene");
  const auto store = dir.path() / "a" / "tent.wbk";
  const auto elsewhere = dir.path() / "models";
  std::filesystem::create_directories(store);
  std::filesystem::create_directories(elsewhere);
  EXPECT_EQ(LocateStoreScene("builtin:furnace", store), "builtin:furnace");
  ::unsetenv("WAVEBAKE_SCENE_PATH");
  EXPECT_EQ(LocateStoreScene("tent.obj", store), "tent.obj");  // nowhere: as named
  std::ofstream(elsewhere / "tent.obj") << "v 0 0 0\n";
  ::setenv("WAVEBAKE_SCENE_PATH", ("/nonexistent:" + elsewhere.string()).c_str(), 1);
  EXPECT_EQ(LocateStoreScene("tent.obj", store), (elsewhere / "tent.obj").string());
  std::ofstream(dir.path() / "a" / "tent.obj") << "v 0 0 0\n";  // beside the store wins
  EXPECT_EQ(LocateStoreScene("tent.obj", store), (dir.path() / "a" / "tent.obj").string());
  // An older store's path, where it still exists, is used as it is.
  EXPECT_EQ(LocateStoreScene((elsewhere / "tent.obj").string(), store),
            (elsewhere / "tent.obj").string());
  ::unsetenv("WAVEBAKE_SCENE_PATH");
}

}  // namespace
}  // namespace wavebake
