// The bake parameters of diffuse bounces: their spelling, range and the
// combinations refused with a reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/bake/bake_param_words.h"
#include "core/bake/bake_params_io.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

BakeParams MeshJob(int bounces) {
  BakeParams p;
  p.layout = "hilbert:32x32";
  p.bounces = bounces;
  return p;
}

absl::StatusOr<int> Bounces(const std::string& word) {
  BakeParamWords words;
  words.words["bounces"] = word;
  absl::StatusOr<BakeParams> p = ParseBakeParamWords(MeshJob(0), words);
  if (!p.ok()) return p.status();
  return p->bounces;
}

TEST(BounceParamsTest, SpelledAsCountsOrAuto) {
  EXPECT_EQ(*Bounces("0"), 0);
  EXPECT_EQ(*Bounces("8"), 8);
  EXPECT_EQ(*Bounces("auto"), kAutoBounces);
  for (const char* bad : {"9", "-1", "two", "", "3x"})
    EXPECT_THAT(Bounces(bad).status().message(), HasSubstr("bounces")) << bad;
}

TEST(BounceParamsTest, RangesAndRefusals) {
  EXPECT_TRUE(ValidateBakeParams(MeshJob(3)).ok());
  EXPECT_THAT(ValidateBakeParams(MeshJob(9)).message(), HasSubstr("bounces"));
  BakeParams rays = MeshJob(1);
  rays.gather_rays = 0;
  EXPECT_THAT(ValidateBakeParams(rays).message(), HasSubstr("gather_rays"));
  // A camera gathers from the meshes' vertices (core/bake/bake_gather.h).
  BakeParams camera = MeshJob(1);
  camera.layout = "camera:64x64";
  EXPECT_TRUE(ValidateBakeParams(camera).ok());
  // The triple product keeps V and ρ apart: nothing can bounce in V.
  BakeParams visibility = MeshJob(kAutoBounces);
  visibility.transport = Transport::kVisibility;
  EXPECT_THAT(ValidateBakeParams(visibility).message(), HasSubstr("triple product"));
  BakeParams uv = MeshJob(2);
  uv.layout = "uv:64x64";
  EXPECT_TRUE(ValidateBakeParams(uv).ok());
}

}  // namespace
}  // namespace wavebake
