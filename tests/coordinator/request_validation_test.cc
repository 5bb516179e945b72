// BakeRequest defaults and field-naming errors (DESIGN.md §4, §5).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "proto/bake_request.h"
#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

using ::testing::StartsWith;

TEST(RequestValidationTest, FillsDefaultsOfDesignSection5) {
  v1::BakeRequest r = testing::BuiltinRequest();
  ASSERT_TRUE(NormalizeBakeRequest(r).ok());
  EXPECT_EQ(r.light_res(), 32);
  EXPECT_EQ(r.layout(), "camera");
  EXPECT_EQ(r.supersample(), 4);
  EXPECT_EQ(r.column_mode(), "adaptive");
  EXPECT_EQ(r.column_filter(), "haar");
  EXPECT_EQ(r.row_filter(), "haar");
  EXPECT_EQ(r.error_scope(), "matrix");
  EXPECT_DOUBLE_EQ(r.target_error(), 0.01);
  EXPECT_EQ(r.bits(), 0);
  EXPECT_EQ(r.seed(), 1u);
  EXPECT_EQ(r.max_attempts(), 3);
  EXPECT_EQ(r.refine(), "on");
  EXPECT_TRUE(ToBakeParams(r)->refine);
  EXPECT_EQ(BuiltinSceneName(r), "furnace");
}

TEST(RequestValidationTest, KeepsExplicitValuesAndSeedZero) {
  v1::BakeRequest r = testing::BuiltinRequest("cubes-wall");
  r.set_light_res(64);
  r.set_layout("hilbert:256x128");
  r.set_column_mode("2d");
  r.set_column_filter("cdf97");
  r.set_row_filter("daub4");
  r.set_error_scope("column");
  r.set_column_terms(64);
  r.set_bits(12);
  r.set_seed(0);
  r.set_refine("off");
  ASSERT_TRUE(NormalizeBakeRequest(r).ok());
  EXPECT_EQ(r.seed(), 0u);
  auto p = ToBakeParams(r);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->light_res, 64);
  EXPECT_EQ(p->layout, "hilbert:256x128");
  EXPECT_EQ(p->column_mode, ColumnMode::k2d);
  EXPECT_EQ(p->column_filter, WaveletFilter::kCdf97);
  EXPECT_EQ(p->row_filter, WaveletFilter::kDaub4);
  EXPECT_EQ(p->error_scope, ErrorScope::kColumn);
  EXPECT_EQ(p->column_terms, 64);
  EXPECT_EQ(p->bits, 12);
  EXPECT_EQ(p->seed, 0u);
  EXPECT_FALSE(p->refine);
  EXPECT_EQ(BuiltinSceneName(r), "cubes-wall");
}

// Refinement follows the cube's faces: a plane domain is traced by brute
// force unless the request asks for refinement, which is an error.
TEST(RequestValidationTest, PlaneDomainDefaultsToBruteForce) {
  v1::BakeRequest r = testing::BuiltinRequest("cubes-wall");
  r.set_light_domain("plane:4");
  const absl::Status s = NormalizeBakeRequest(r);
  ASSERT_TRUE(s.ok()) << s;
  EXPECT_EQ(r.refine(), "off");
  EXPECT_FALSE(ToBakeParams(r)->refines());
  BakeParams p;
  p.light_domain = *ParseLightDomain("plane:4");
  EXPECT_EQ(ToBakeRequest(p).refine(), "off");  // asked for, but not on a plane
}

// Refinement integrates cosines: visibility rows are traced by brute force,
// and asking for refinement with them is an error naming the field.
TEST(RequestValidationTest, VisibilityTransportDefaultsToBruteForce) {
  v1::BakeRequest r = testing::BuiltinRequest("cubes-wall");
  r.set_transport("visibility");
  ASSERT_TRUE(NormalizeBakeRequest(r).ok());
  EXPECT_EQ(r.refine(), "off");
  EXPECT_FALSE(ToBakeParams(r)->refines());
  r.set_refine("on");
  const absl::Status s = NormalizeBakeRequest(r);
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(s.message()), ::testing::StartsWith("refine: "));
  BakeParams p;
  p.transport = Transport::kVisibility;
  EXPECT_EQ(ToBakeRequest(p).refine(), "off");
}

TEST(RequestValidationTest, ErrorsStartWithTheField) {
  const std::vector<std::pair<std::function<void(v1::BakeRequest&)>, std::string>> cases = {
      {[](auto& r) { r.set_light_res(512); }, "light_res: "},
      {[](auto& r) { r.set_light_res(4); }, "light_res: "},
      {[](auto& r) { r.set_layout("grid:64x64"); }, "layout: "},
      {[](auto& r) { r.set_layout("camera:0x64"); }, "layout: "},
      {[](auto& r) { r.set_target_error(1.5); }, "target_error: "},
      {[](auto& r) { r.set_column_terms(-1); }, "column_terms: "},
      {[](auto& r) { r.set_bits(1); }, "bits: "},
      {[](auto& r) { r.set_tile_size(48); }, "tile_size: "},
      {[](auto& r) { r.set_column_group(100000); }, "column_group: "},
      {[](auto& r) { r.set_error_scope("row"); }, "error_scope: "},
      {[](auto& r) { r.set_row_filter("cdf97"); }, "row_filter: "},
      {[](auto& r) { r.set_refine("yes"); }, "refine: "},
      {[](auto& r) { r.set_light_domain("plane:4"), r.set_refine("on"); }, "refine: "},
      {[](auto& r) { r.set_output_name(".hidden"); }, "output_name: "},
      {[](auto& r) { r.mutable_scene()->mutable_uploaded()->set_sha256("abc"); },
       "scene.uploaded.sha256: "},
      // The core's rules apply too: what Submit accepts, every worker can bake.
      {[](auto& r) { r.set_layout("hilbert"); }, "layout: "},
      {[](auto& r) { r.set_layout("camera:8192x8192"); }, "layout: "},
      {[](auto& r) { r.set_tile_size(512); }, "tile_size: "},
      {[](auto& r) { r.set_column_filter("daub4"); }, "column_filter: "},
  };
  for (const auto& [edit, prefix] : cases) {
    v1::BakeRequest r = testing::BuiltinRequest();
    edit(r);
    absl::Status s = NormalizeBakeRequest(r);
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument) << prefix;
    EXPECT_THAT(std::string(s.message()), StartsWith(prefix));
  }
}

// Every BakeParams field a request carries survives the trip through the
// request (clients build requests from flags, workers read them back).
TEST(RequestValidationTest, ParamsRoundTripThroughTheRequest) {
  BakeParams p;
  p.light_res = 16;
  p.layout = "hilbert:64x32";
  p.supersample = 9;
  p.row_filter = WaveletFilter::kDaub4;
  p.column_mode = ColumnMode::kFull;
  p.column_filter = WaveletFilter::kLeGall53;
  p.target_error = 0.05;
  p.error_scope = ErrorScope::kColumn;
  p.column_terms = 7;
  p.bits = 11;
  p.seed = 0;
  p.tile_size = 8;
  p.column_group = 100;
  v1::BakeRequest r = ToBakeRequest(p);
  r.mutable_scene()->set_builtin("builtin:furnace");
  absl::StatusOr<BakeParams> back = ToBakeParams(r);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->light_res, p.light_res);
  EXPECT_EQ(back->layout, p.layout);
  EXPECT_EQ(back->supersample, p.supersample);
  EXPECT_EQ(back->row_filter, p.row_filter);
  EXPECT_EQ(back->column_mode, p.column_mode);
  EXPECT_EQ(back->column_filter, p.column_filter);
  EXPECT_EQ(back->target_error, p.target_error);
  EXPECT_EQ(back->error_scope, p.error_scope);
  EXPECT_EQ(back->column_terms, p.column_terms);
  EXPECT_EQ(back->bits, p.bits);
  EXPECT_EQ(back->seed, p.seed);
  EXPECT_EQ(back->tile_size, p.tile_size);
  EXPECT_EQ(back->column_group, p.column_group);
}

TEST(RequestValidationTest, PartialStoreIsHiddenBesideTheStore) {
  EXPECT_EQ(PartialStorePath("cubes.wbk"), ".cubes.wbk.partial");
  EXPECT_EQ(PartialStorePath("team/cubes.wbk"), "team/.cubes.wbk.partial");
}

}  // namespace
}  // namespace wavebake
