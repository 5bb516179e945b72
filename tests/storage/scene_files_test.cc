// What a scene file may make the loader read (storage/scene_files/scene_files.h): an
// uploaded scene only files under its confined root — no absolute path, no
// "..", no OBJ material library elsewhere — with messages that name no
// server path; the local user's scene reads anything, with a warning.
#include "storage/scene_files/scene_files.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "storage/scene_files/scene_loader.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr char kTriangle[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

class SceneFilesTest : public ::testing::Test {
 protected:
  SceneFilesTest() : root_(dir_.path() / "upload") { fs::create_directories(root_); }
  static std::string Write(const fs::path& p, const std::string& text) {
    std::ofstream(p) << text;
    return p.string();
  }
  // The JSON scene {"meshes": [{"file": reference}]} in the confined root.
  std::string JsonReferring(const std::string& reference) {
    return Write(root_ / "scene.json", R"({"meshes": [{"file": )" + Quoted(reference) + "}]}");
  }
  static std::string Quoted(const std::string& s) { return "\"" + s + "\""; }
  absl::StatusOr<Scene> LoadConfined(const std::string& spec, SceneReport* report = nullptr) {
    const std::unique_ptr<SceneFiles> files = ConfinedSceneFiles(root_);
    return LoadScene(spec, report, files.get());
  }

  test_support::ScratchDir dir_{"scene_files"};
  fs::path root_;
};

TEST_F(SceneFilesTest, UploadedJsonMayNotNameAnAbsolutePathOrLeaveItsDirectory) {
  // Files that exist outside the upload: what the hole exposed.
  const std::string outside = Write(dir_.path() / "secret.obj", kTriangle);
  fs::create_directories(root_ / "sub");
  for (const std::string& reference :
       {outside, std::string("../secret.obj"), std::string("sub/../../secret.obj"),
        std::string("/etc/passwd"), std::string("../../../../../../etc/passwd")}) {
    const absl::StatusOr<Scene> scene = LoadConfined(JsonReferring(reference));
    ASSERT_FALSE(scene.ok()) << reference;
    EXPECT_EQ(scene.status().code(), absl::StatusCode::kInvalidArgument) << reference;
    const std::string message(scene.status().message());
    EXPECT_THAT(message, HasSubstr("meshes[0].file")) << message;
    EXPECT_THAT(message, HasSubstr(reference.starts_with("/") ? "absolute" : "\"..\"")) << message;
    EXPECT_THAT(message, Not(HasSubstr(root_.string()))) << message;
  }
}

TEST_F(SceneFilesTest, UploadedJsonReadsWhatWasUploadedWithIt) {
  fs::create_directories(root_ / "meshes");
  Write(root_ / "meshes" / "tri.obj", kTriangle);
  const absl::StatusOr<Scene> scene = LoadConfined(JsonReferring("meshes/tri.obj"));
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(scene->meshes.size(), 1u);

  const absl::StatusOr<Scene> missing = LoadConfined(JsonReferring("gone.obj"));
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(std::string(missing.status().message()),
              HasSubstr("meshes[0].file: 'gone.obj' was not uploaded with the scene"));
  EXPECT_THAT(std::string(missing.status().message()), Not(HasSubstr(root_.string())));
}

TEST_F(SceneFilesTest, ObjMaterialLibraryOutsideTheUploadIsNotRead) {
  Write(dir_.path() / "red.mtl", "newmtl red\nKd 0.7 0.2 0.1\n");
  const std::string obj = Write(
      root_ / "red.obj", std::string("mtllib ../red.mtl\n") + kTriangle + "usemtl red\nf 1 3 2\n");
  const absl::StatusOr<Scene> local = LoadScene(obj);
  ASSERT_TRUE(local.ok()) << local.status();
  EXPECT_EQ(local->meshes.at(0).albedo, (Vec3{0.7f, 0.2f, 0.1f})) << "the local user's own file";

  const absl::StatusOr<Scene> confined = LoadConfined(obj);
  ASSERT_TRUE(confined.ok()) << confined.status();
  // assimp makes up material "red" without its library: not the outside colour.
  for (const Mesh& m : confined->meshes)
    EXPECT_NE(m.albedo, (Vec3{0.7f, 0.2f, 0.1f})) << "read ../red.mtl";
}

TEST_F(SceneFilesTest, UploadedSceneErrorsNameNoServerPath) {
  const std::string nan = Write(root_ / "nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
  const std::string junk = Write(root_ / "junk.ply", "ply\nformat nonsense\n");
  const std::string outside = Write(dir_.path() / "outside.obj", kTriangle);
  for (const std::string& spec : {nan, junk, outside}) {
    const absl::StatusOr<Scene> scene = LoadConfined(spec);
    ASSERT_FALSE(scene.ok()) << spec;
    EXPECT_EQ(scene.status().code(), absl::StatusCode::kInvalidArgument);
    const std::string message(scene.status().message());
    EXPECT_THAT(message, HasSubstr(fs::path(spec).filename().string()));
    EXPECT_THAT(message, Not(HasSubstr(dir_.path().string()))) << message;
  }
}

TEST_F(SceneFilesTest, LocalScenesReadAnythingButWarn) {
  const std::string outside = Write(dir_.path() / "tri.obj", kTriangle);
  for (const std::string& reference : {outside, std::string("../tri.obj")}) {
    SceneReport report;
    const absl::StatusOr<Scene> scene = LoadScene(JsonReferring(reference), &report);
    ASSERT_TRUE(scene.ok()) << scene.status();
    ASSERT_EQ(report.warnings.size(), 1u) << reference;
    EXPECT_THAT(report.warnings[0], HasSubstr("meshes[0].file"));
    EXPECT_THAT(report.warnings[0], HasSubstr("a remote job refuses it"));
  }
  SceneReport report;
  Write(root_ / "tri.obj", kTriangle);
  ASSERT_TRUE(LoadScene(JsonReferring("tri.obj"), &report).ok());
  EXPECT_TRUE(report.warnings.empty()) << report.warnings[0];
}

TEST(UnsafeReferenceTest, AbsoluteAndDotDotAreUnsafe) {
  EXPECT_EQ(UnsafeReference("a/b.obj"), "");
  EXPECT_EQ(UnsafeReference("./b.obj"), "");
  EXPECT_EQ(UnsafeReference("b..obj"), "") << "a name with dots is a name";
  EXPECT_THAT(UnsafeReference("/b.obj"), HasSubstr("absolute"));
  EXPECT_THAT(UnsafeReference("a/../b.obj"), HasSubstr(".."));
  EXPECT_THAT(UnsafeReference(".."), HasSubstr(".."));
  EXPECT_THAT(UnsafeReference(""), HasSubstr("empty"));
}

}  // namespace
}  // namespace wavebake
