// The bake parameters spelled in words (core/bake/bake_param_words.h): every word
// lands in its field, and a bad one is refused naming the field it was for.
#include "core/bake/bake_param_words.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <tuple>

namespace wavebake {
namespace {

using ::testing::StartsWith;

TEST(BakeParamWordsTest, EveryWordLandsInItsField) {
  BakeParamWords w;
  w.words = {{"row_filter", "daub4"},
             {"column_mode", "2d"},
             {"column_filter", "cdf97"},
             {"error_scope", "column"},
             {"bits", "12"},
             {"level_scaling", "paper"},
             {"refine", "off"},
             {"light_domain", "plane:4"},
             {"layout", "grid"}};
  absl::StatusOr<BakeParams> p = ParseBakeParamWords(BakeParams{}, w);
  ASSERT_TRUE(p.ok()) << p.status();
  EXPECT_EQ(p->row_filter, WaveletFilter::kDaub4);
  EXPECT_EQ(p->column_mode, ColumnMode::k2d);
  EXPECT_EQ(p->column_filter, WaveletFilter::kCdf97);
  EXPECT_EQ(p->error_scope, ErrorScope::kColumn);
  EXPECT_EQ(p->bits, 12);
  EXPECT_EQ(p->level_scaling, LevelScaling::kPaper);
  EXPECT_FALSE(p->refine);
  EXPECT_TRUE(p->light_domain.is_plane());
  EXPECT_EQ(p->layout, "grid");
  EXPECT_EQ(ParseBakeParamWords(BakeParams{}, BakeParamWords{})->bits, 0);  // auto
}

TEST(BakeParamWordsTest, ABadWordNamesItsField) {
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"row_filter", "cdf97", "row_filter: "},
      {"column_filter", "daub9", "column_filter: "},
      {"column_mode", "fast", "column_mode: "},
      {"bits", "12x", "bits: "},
      {"bits", "0", "bits: "},
      {"bits", "1", "bits: "},
      {"refine", "maybe", "refine: "},
      {"transport", "glossy", "transport: "},
      {"light_domain", "plane:1", "light_domain: "},
      {"layout", "spiral", "layout"},
      {"light_res", "32", "light_res: "},  // a number, not a word
  };
  for (const auto& [word, value, field] : cases) {
    BakeParamWords w;
    w.words[word] = value;
    const absl::Status s = ParseBakeParamWords(BakeParams{}, w).status();
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument) << field;
    EXPECT_THAT(std::string(s.message()), StartsWith(field));
  }
}

TEST(BakeParamWordsTest, TheWholeIsValidatedAndUvOverlapJoinsTheLayout) {
  BakeParams numbers;
  numbers.light_res = 12;  // not a power of two
  EXPECT_THAT(std::string(ParseBakeParamWords(numbers, {}).status().message()),
              StartsWith("light_res"));
  numbers = BakeParams{};
  numbers.layout = "uv:64x64";
  BakeParamWords w;
  w.allow_uv_overlap = true;
  absl::StatusOr<BakeParams> p = ParseBakeParamWords(numbers, w);
  ASSERT_TRUE(p.ok()) << p.status();
  EXPECT_THAT(p->layout, ::testing::HasSubstr("allow-overlap"));
}

}  // namespace
}  // namespace wavebake
