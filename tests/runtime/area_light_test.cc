#include "runtime/near_field/area_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/wavelets/wavelet2d.h"
#include "runtime/near_field/light_canvas.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake {
namespace {

using TempDir = test_support::ScratchDir;

std::filesystem::path Write(const TempDir& dir, const std::string& name, const std::string& text) {
  const auto p = dir.path() / name;
  std::ofstream(p) << text;
  return p;
}

TEST(AreaLight, ReadsOneLightOrAnArray) {
  TempDir dir;
  absl::StatusOr<std::vector<AreaLight>> one = LoadAreaLights(
      Write(dir, "a.json",
            R"({"centre": [0.5, -1], "height": 2, "size": [1, 0.5], "rotation_degrees": 30,
                "radiance": [1, 2, 3], "resolution": 64})"));
  ASSERT_TRUE(one.ok()) << one.status();
  ASSERT_EQ(one->size(), 1u);
  EXPECT_EQ((*one)[0].centre[1], -1);
  EXPECT_EQ((*one)[0].size[1], 0.5);
  EXPECT_EQ((*one)[0].radiance.z, 3);
  EXPECT_EQ((*one)[0].resolution, 64);
  EXPECT_EQ((*one)[0].texture.width, 0);
  absl::StatusOr<std::vector<AreaLight>> two = LoadAreaLights(Write(
      dir, "b.json",
      R"([{"centre": [0, 0], "height": 1, "size": [1, 1]}, {"centre": [1, 1], "height": 3, "size": [2, 2]}])"));
  ASSERT_TRUE(two.ok()) << two.status();
  EXPECT_EQ(two->size(), 2u);
  EXPECT_EQ((*two)[1].height, 3);
}

TEST(AreaLight, ErrorsNameTheFileAndTheField) {
  TempDir dir;
  const struct {
    const char* json;
    const char* field;
  } cases[] = {
      {R"({"centre": [0, 0], "height": 1, "size": [1, 1], "colour": [1, 1, 1]})",
       "colour: unknown key"},
      {R"({"height": 1, "size": [1, 1]})", "centre: missing"},
      {R"({"centre": [0, 0], "height": 1, "size": [1, 0]})", "size: edges must be > 0"},
      {R"({"centre": [0], "height": 1, "size": [1, 1]})", "centre: expected an array of 2"},
      {R"({"centre": [0, 0], "height": 1, "size": [1, 1], "resolution": 48})", "resolution: 48"},
      {R"({"centre": [0, 0], "height": 1, "size": [1, 1], "texture": "nope.png"})",
       "texture: no such file"},
      {R"({"centre": [0, 0], "height": 1, "size": [1, 1], "radiance": [1, -1, 1]})",
       "radiance: must be"},
      {R"([])", "lights: the array is empty"},
  };
  for (const auto& c : cases) {
    const auto path = Write(dir, "bad.json", c.json);
    absl::StatusOr<std::vector<AreaLight>> l = LoadAreaLights(path);
    ASSERT_FALSE(l.ok()) << c.json;
    EXPECT_NE(l.status().message().find(path.string()), std::string::npos) << l.status();
    EXPECT_NE(l.status().message().find(c.field), std::string::npos) << l.status();
  }
}

TEST(AreaLight, SequenceInterpolatesAndKeepsTheTexture) {
  TempDir dir;
  absl::StatusOr<AreaLightSequence> seq = LoadAreaLightSequence(
      Write(dir, "s.json",
            R"({"frames": 5, "from": {"centre": [0, 0], "height": 1, "size": [1, 2]},
                "to": {"centre": [4, -4], "size": [3, 2], "rotation_degrees": 90}})"));
  ASSERT_TRUE(seq.ok()) << seq.status();
  const AreaLight mid = seq->Frame(2);
  EXPECT_DOUBLE_EQ(mid.centre[0], 2);
  EXPECT_DOUBLE_EQ(mid.centre[1], -2);
  EXPECT_DOUBLE_EQ(mid.size[0], 2);
  EXPECT_DOUBLE_EQ(mid.height, 1);  // "to" kept it
  EXPECT_DOUBLE_EQ(mid.rotation_degrees, 45);
  EXPECT_DOUBLE_EQ(seq->Frame(4).centre[0], 4);
  EXPECT_FALSE(LoadAreaLightSequence(
                   Write(dir, "t.json",
                         R"({"frames": 2, "from": {"centre": [0, 0], "height": 1, "size": [1, 1]},
                             "to": {"resolution": 64}})"))
                   .ok());
}

// An unrotated light whose texture has R pixels per edge is its texture on
// the canvas exactly; a constant light's canvas is its radiance everywhere,
// so its row transform is one DC coefficient (R × radiance) and nothing else.
TEST(LightCanvas, DrawsTheLightAndKeepsTheLargestSources) {
  AreaLight l;
  l.centre = {1, 2};
  l.size = {2, 1};
  l.resolution = 4;
  l.radiance = {2, 2, 2};
  l.texture = EnvMap{4, 4, std::vector<float>(48)};
  for (int i = 0; i < 48; ++i) l.texture.rgb[i] = float(i % 7) / 7;
  const LightCanvas c = DrawLight(l);
  EXPECT_DOUBLE_EQ(c.s0, 0);
  EXPECT_DOUBLE_EQ(c.t0, 1.5);
  EXPECT_DOUBLE_EQ(c.extent_s, 2);
  for (int i = 0; i < 48; ++i) EXPECT_NEAR(c.rgb[i], 2 * l.texture.rgb[i], 1e-6) << i;

  l.texture = EnvMap{};
  l.rotation_degrees = 90;  // the bounding box turns with it
  const LightCanvas flat = DrawLight(l);
  EXPECT_NEAR(flat.extent_s, 1, 1e-9);
  EXPECT_NEAR(flat.extent_t, 2, 1e-9);
  const std::vector<SourceTerm> terms = SelectSources(flat, 1);
  ASSERT_EQ(terms.size(), 1u);
  EXPECT_EQ(terms[0].x, 0);
  EXPECT_NEAR(terms[0].rgb[0], 4 * 2, 1e-4);  // R × mean radiance
}

}  // namespace
}  // namespace wavebake
