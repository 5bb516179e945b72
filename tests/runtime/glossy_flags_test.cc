// The glossy command-line values: --view and --brdf-sequence
// (runtime/glossy/glossy_store.h, runtime/glossy/material_sequence.h).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "runtime/glossy/glossy_store.h"
#include "runtime/glossy/material_sequence.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

TEST(ParseView, ReadsAnEyeAndNamesTheFlag) {
  const absl::StatusOr<Vec3> eye = ParseView("0.5,-2,3e1");
  ASSERT_TRUE(eye.ok()) << eye.status();
  EXPECT_EQ(*eye, (Vec3{0.5f, -2, 30}));
  for (const char* bad : {"", "1,2", "1,2,3,4", "a,b,c", "1,nan,2", "1,,2"})
    EXPECT_THAT(ParseView(bad).status().message(), HasSubstr("view")) << bad;
}

TEST(ParseBrdfSequence, ExponentsMoveGeometricallyRoughnessLinearly) {
  const absl::StatusOr<BrdfSequence> p = ParseBrdfSequence("phong:8:128:5:2");
  ASSERT_TRUE(p.ok()) << p.status();
  EXPECT_EQ(p->total(), 7);
  EXPECT_EQ(p->At(0), "phong:8");
  EXPECT_EQ(p->At(2), "phong:32");  // 8 · 16^(1/2)
  EXPECT_EQ(p->At(4), "phong:128");
  EXPECT_EQ(p->At(6), "phong:128");  // held
  const absl::StatusOr<BrdfSequence> g = ParseBrdfSequence("ggx:0.1:0.5:5");
  ASSERT_TRUE(g.ok()) << g.status();
  EXPECT_EQ(g->At(2), "ggx:0.3");
  EXPECT_EQ(ParseBrdfSequence("blinn:4:4:1")->At(0), "blinn:4");
}

TEST(ParseBrdfSequence, ErrorsNameTheFlag) {
  for (const char* bad : {"phong:8:128", "lambert:1:2:3", "phong:8:x:3", "phong:8:128:0",
                          "phong:8:128:3:-1", "ggx:0.1:3:4", "phong:-1:8:2"}) {
    const absl::StatusOr<BrdfSequence> s = ParseBrdfSequence(bad);
    ASSERT_FALSE(s.ok()) << bad;
    EXPECT_THAT(s.status().message(), HasSubstr("brdf-sequence")) << bad;
  }
}

}  // namespace
}  // namespace wavebake
