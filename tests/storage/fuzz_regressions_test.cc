// Every input the scene fuzzers found (tests/fuzz/{obj,ply,json}/corpus/
// regression-*), replayed in the normal suite: each loads or is refused as
// bad input, confined to its upload directory. Before their fixes one
// crashed assimp (an out-of-range PLY face index) and two hung it (PLY
// headers without end_header, one behind a "ply?" magic): each must end
// within a bound.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "storage/scene_files/scene_files.h"
#include "storage/scene_files/scene_loader.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake {
namespace {

namespace fs = std::filesystem;

TEST(FuzzRegressionsTest, SceneInputsTheFuzzersFoundLoadOrAreRefused) {
  test_support::ScratchDir dir("fuzz_regressions");
  std::ofstream(dir.path() / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::unique_ptr<SceneFiles> files = ConfinedSceneFiles(dir.path());
  int replayed = 0;
  for (const char* format : {"obj", "ply", "json"}) {
    const fs::path corpus = fs::path(WB_SOURCE_DIR) / "tests/fuzz" / format / "corpus";
    for (const fs::directory_entry& e : fs::directory_iterator(corpus)) {
      if (!e.path().filename().string().starts_with("regression-")) continue;
      const fs::path scene = dir.path() / (std::string("scene.") + format);
      fs::copy_file(e.path(), scene, fs::copy_options::overwrite_existing);
      const auto start = std::chrono::steady_clock::now();
      const absl::StatusOr<Scene> s = LoadScene(scene.string(), nullptr, files.get());
      EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10)) << e.path();
      if (!s.ok()) {
        EXPECT_EQ(s.status().code(), absl::StatusCode::kInvalidArgument) << e.path();
      }
      ++replayed;
    }
  }
  EXPECT_GE(replayed, 5);
}

}  // namespace
}  // namespace wavebake
