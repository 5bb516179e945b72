#include "core/scene/scene_hash.h"

#include <gtest/gtest.h>

#include <set>

#include "core/scene/builtin_scenes.h"

namespace wavebake {
namespace {

Scene Sphere() { return *MakeBuiltinScene("sphere-plane"); }

TEST(SceneHash, Is32HexDigitsAndRepeatable) {
  const std::string h = SceneHash(Sphere());
  ASSERT_EQ(h.size(), 32u);
  EXPECT_EQ(h.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_EQ(SceneHash(Sphere()), h);
}

TEST(SceneHash, SeesEveryBakeInput) {
  const std::string base = SceneHash(Sphere());
  auto changed = [&](auto edit) {
    Scene s = Sphere();
    edit(s);
    return SceneHash(s) != base;
  };
  // Ground vertex (63, 63) at x = 1.9375 moved by 1e-6 (≈ 4 float ulps there).
  EXPECT_TRUE(changed([](Scene& s) { s.meshes[0].positions.back().x += 1e-6f; }));
  EXPECT_TRUE(changed([](Scene& s) { s.meshes[1].normals[7].y += 1e-6f; }));
  EXPECT_TRUE(changed([](Scene& s) { s.meshes[1].albedo.z = 0.26f; }));
  EXPECT_TRUE(changed(
      [](Scene& s) { std::swap(s.meshes[1].triangles[3][1], s.meshes[1].triangles[3][2]); }));
  EXPECT_TRUE(changed([](Scene& s) { s.meshes[0].triangles.pop_back(); }));
  EXPECT_TRUE(changed([](Scene& s) { s.meshes[0].grid_width = s.meshes[0].grid_height = 0; }));
  EXPECT_TRUE(changed([](Scene& s) { s.camera->fov_y_degrees = 46; }));
  EXPECT_TRUE(changed([](Scene& s) { s.camera.reset(); }));
  EXPECT_TRUE(changed([](Scene& s) { std::swap(s.meshes[0], s.meshes[1]); }));
  // Names are not content.
  EXPECT_FALSE(changed([](Scene& s) {
    s.name = "other";
    s.meshes[1].name = "ball";
  }));
}

TEST(SceneHash, DistinguishesTheBuiltins) {
  std::set<std::string> hashes;
  for (const std::string& name : BuiltinSceneNames())
    hashes.insert(SceneHash(*MakeBuiltinScene(name)));
  EXPECT_EQ(hashes.size(), BuiltinSceneNames().size());
}

TEST(SceneHash, NegativeZeroIsZero) {
  Scene a = *MakeBuiltinScene("furnace");
  Scene b = a;
  b.meshes[0].positions[0].y = -0.0f;
  a.meshes[0].positions[0].y = 0.0f;
  EXPECT_EQ(SceneHash(a), SceneHash(b));
}

}  // namespace
}  // namespace wavebake
