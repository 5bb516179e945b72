// The table of bake parameters (core/bake/bake_param_table.h) against the
// places derived from it: every BakeRequest field is a row or one of the
// request's own fields, of the type the row's kind needs; a value other than
// the default of every row survives the request and the store's .zattrs; the
// .zattrs keys are the rows' names under their Record rules.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/bake/bake_param_words.h"
#include "core/bake/bake_params_io.h"
#include "proto/bake_request.h"
#include "storage/store/params_json.h"

namespace wavebake {
namespace {

using google::protobuf::FieldDescriptor;

std::set<std::string> RowNames(bool request_only) {
  std::set<std::string> names;
  params::ForEach([&](const auto& row) {
    if (!request_only || row.info.in_request) names.insert(std::string(row.info.name));
  });
  return names;
}

TEST(BakeParamTableTest, EveryRequestFieldIsARowOfAMatchingType) {
  const google::protobuf::Descriptor* d = v1::BakeRequest::descriptor();
  std::set<std::string> fields;
  for (int i = 0; i < d->field_count(); ++i) fields.insert(d->field(i)->name());
  // The request's own fields: what to bake and how the service runs it
  // (update_scene: the old job's scene, as `scene`, set by the coordinator).
  for (const char* own : {"scene", "max_attempts", "output_name", "update_scene"})
    fields.erase(own);
  EXPECT_EQ(fields, RowNames(/*request_only=*/true));

  params::ForEach([&](const auto& row) {
    if (!row.info.in_request) return;
    const FieldDescriptor* f = d->FindFieldByName(std::string(row.info.name));
    ASSERT_NE(f, nullptr) << row.info.name;
    const bool number = f->cpp_type() == FieldDescriptor::CPPTYPE_INT32 ||
                        f->cpp_type() == FieldDescriptor::CPPTYPE_UINT64 ||
                        f->cpp_type() == FieldDescriptor::CPPTYPE_DOUBLE;
    const bool flag = f->cpp_type() == FieldDescriptor::CPPTYPE_BOOL;
    const bool words = f->cpp_type() == FieldDescriptor::CPPTYPE_STRING;
    using Row = std::decay_t<decltype(row)>;
    if constexpr (std::is_same_v<Row, params::Switch>)
      EXPECT_TRUE(params::InWords(row) ? words : flag) << row.info.name;
    else if constexpr (std::is_same_v<Row, params::Number<int>> ||
                       std::is_same_v<Row, params::Number<uint64_t>> ||
                       std::is_same_v<Row, params::Number<double>>)
      EXPECT_TRUE(number) << row.info.name;
    else
      EXPECT_TRUE(words) << row.info.name;
  });
}

// Parameters unlike BakeParams{} in every row, valid together.
BakeParams Unusual() {
  BakeParams p;
  p.light_res = 16;
  p.light_domain = *ParseLightDomain("plane:4:-Z");
  p.layout = "hilbert:32x16";
  p.supersample = 9;
  p.row_filter = WaveletFilter::kDaub4;
  p.column_mode = ColumnMode::kFull;
  p.column_filter = WaveletFilter::kCdf97;
  p.target_error = 0.25;
  p.error_scope = ErrorScope::kColumn;
  p.column_terms = 7;
  p.bits = 9;
  p.level_scaling = LevelScaling::kPaper;
  p.seed = 18446744073709551557ull;  // beyond a double's 53 bits
  p.refine = false;
  p.bounces = 3;
  p.gather_rays = 64;
  p.keep_staging = true;
  p.tile_size = 8;
  p.column_group = 300;
  return p;
}

TEST(BakeParamTableTest, EveryRowSurvivesTheRequest) {
  const BakeParams p = Unusual();
  ASSERT_TRUE(ValidateBakeParams(p).ok()) << ValidateBakeParams(p);
  v1::BakeRequest r = ToBakeRequest(p);
  r.mutable_scene()->set_builtin("builtin:furnace");
  absl::StatusOr<BakeParams> back = ToBakeParams(r);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(ToJson(*back), ToJson(p));
  EXPECT_EQ(back->seed, p.seed);
  EXPECT_TRUE(back->keep_staging);
  // The one row without a request field comes back as its default.
  EXPECT_EQ(back->ray_epsilon, 0);
}

TEST(BakeParamTableTest, EveryRecordedRowSurvivesTheStore) {
  BakeParams p = Unusual();
  p.ray_epsilon = 0.125f;
  const nlohmann::json j = ToJson(p);
  absl::StatusOr<BakeParams> back = BakeParamsFromJson(j);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(ToJson(*back), j);
  EXPECT_EQ(back->ray_epsilon, 0.125f);
  EXPECT_FALSE(back->keep_staging);  // Record::kNever
  std::set<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.insert(k);
  std::set<std::string> recorded;
  params::ForEach([&](const auto& row) {
    if (row.info.record != params::Record::kNever) recorded.insert(std::string(row.info.name));
  });
  // Not written: the two rows whose values here are what a store without
  // them means (brute force, diffuse: a visibility transport needs haar rows
  // and the cube, unlike the rest).
  for (const char* name : {"refine", "transport"}) recorded.erase(name);
  EXPECT_EQ(keys, recorded);
}

TEST(BakeParamTableTest, DefaultStoresKeepTheirKeysAndOlderStoresRead) {
  // Rows added after stores existed are written only away from the value a
  // store without them means, so a default store's .zattrs is unchanged.
  const nlohmann::json j = ToJson(BakeParams{});
  EXPECT_EQ(j["refine"], "on");  // the default refines
  EXPECT_FALSE(j.contains("transport"));
  EXPECT_FALSE(j.contains("light_domain"));
  EXPECT_EQ(j["bits"], "auto");
  nlohmann::json older = j;
  older.erase("refine");  // a store from before refinement: brute force
  absl::StatusOr<BakeParams> back = BakeParamsFromJson(older);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_FALSE(back->refine);
  nlohmann::json missing = j;
  missing.erase("light_res");
  EXPECT_THAT(std::string(BakeParamsFromJson(missing).status().message()),
              ::testing::StartsWith("params.light_res: missing"));
}

// An update's refusal names the first parameter that differs by the values a
// user gave, a row the record leaves out by the value its absence means.
TEST(BakeParamTableTest, ADifferenceNamesWhatAnAbsentRowMeans) {
  BakeParams bounced;
  bounced.bounces = 1;
  EXPECT_EQ(FirstParameterDifference(ToJson(BakeParams{}), ToJson(BakeParams{})), "");
  EXPECT_THAT(FirstParameterDifference(ToJson(BakeParams{}), ToJson(bounced)),
              ::testing::StartsWith("parameter bounces is 0 there and 1 here"));
  EXPECT_THAT(FirstParameterDifference(ToJson(bounced), ToJson(BakeParams{})),
              ::testing::StartsWith("parameter bounces is 1 there and 0 here"));
  // The same value written out or left out is no difference.
  nlohmann::json explicit_default = ToJson(BakeParams{});
  explicit_default["bounces"] = 0;
  EXPECT_EQ(FirstParameterDifference(explicit_default, ToJson(BakeParams{})), "");
}

TEST(BakeParamTableTest, TheRangesOfTheTableAreEnforcedEverywhere) {
  BakeParams p;
  p.tile_size = 3;
  EXPECT_THAT(std::string(ValidateBakeParams(p).message()),
              ::testing::StartsWith("tile_size: 3 is not a power of two in 4..256"));
  v1::BakeRequest r = ToBakeRequest(BakeParams{});
  r.mutable_scene()->set_builtin("builtin:furnace");
  r.set_supersample(300);
  EXPECT_THAT(std::string(NormalizeBakeRequest(r).message()),
              ::testing::StartsWith("supersample: 300 is outside 1..256"));
  nlohmann::json j = ToJson(BakeParams{});
  j["column_group"] = 70000;
  EXPECT_THAT(std::string(BakeParamsFromJson(j).status().message()),
              ::testing::StartsWith("params.column_group: 70000 is outside 1..65536"));
}

}  // namespace
}  // namespace wavebake
