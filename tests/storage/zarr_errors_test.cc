// Bad inputs get clear errors that name the file or field (DESIGN.md §4).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "storage/zarr/zarr_array.h"
#include "tests/storage/test_support.h"

namespace wavebake {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::TempDir;

void WriteText(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

TEST(ZarrErrorsTest, OpeningANonArrayDirectory) {
  TempDir tmp;
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(tmp.path());
  EXPECT_TRUE(absl::IsNotFound(a.status()));
  EXPECT_THAT(a.status().message(), AllOf(HasSubstr(tmp.path().string()), HasSubstr(".zarray")));
  ASSERT_TRUE(WriteGroup(tmp.path()).ok());  // a group is not an array either
  EXPECT_TRUE(absl::IsNotFound(ZarrArray::Open(tmp.path()).status()));
}

TEST(ZarrErrorsTest, MalformedMetadataNamesFileAndField) {
  TempDir tmp;
  const struct {
    std::string body, field;
  } cases[] = {
      {"not json", "JSON"},
      {R"({"zarr_format": 2, "shape": [4], "chunks": [2], "dtype": "<f8",
           "compressor": {"id": "zstd", "level": 1}, "fill_value": 0, "order": "C"})",
       "dtype"},
      {R"({"zarr_format": 2, "shape": [4], "chunks": [2], "dtype": "<f4",
           "compressor": {"id": "blosc"}, "fill_value": 0, "order": "C"})",
       "compressor"},
      {R"({"zarr_format": 2, "shape": [4], "chunks": [2], "dtype": "<f4",
           "compressor": null, "fill_value": 0, "order": "C"})",
       "compressor"},
      {R"({"zarr_format": 3, "shape": [4], "chunks": [2], "dtype": "<f4",
           "compressor": {"id": "zstd"}, "fill_value": 0, "order": "C"})",
       "zarr_format"},
      {R"({"zarr_format": 2, "shape": [4], "chunks": [2], "dtype": "<f4",
           "compressor": {"id": "zstd"}, "fill_value": 0, "order": "F"})",
       "order"},
      {R"({"zarr_format": 2, "shape": [4, 4], "chunks": [2], "dtype": "<f4",
           "compressor": {"id": "zstd"}, "fill_value": 0, "order": "C"})",
       "chunks"},
      {R"({"zarr_format": 2, "shape": "4", "chunks": [2], "dtype": "<f4",
           "compressor": {"id": "zstd"}, "fill_value": 0, "order": "C"})",
       "shape"},
      {R"({"zarr_format": 2, "shape": [4], "chunks": [2], "dtype": "<i4",
           "compressor": {"id": "zstd"}, "fill_value": 0.5, "order": "C"})",
       "fill_value"},
      {R"({"zarr_format": 2, "shape": [4], "chunks": [2], "dtype": "<f4",
           "compressor": {"id": "zstd"}, "fill_value": 0, "order": "C",
           "filters": [{"id": "shuffle"}]})",
       "filters"},
      {R"({"zarr_format": "2"})", "zarr_format"},  // wrong JSON type, not a crash
  };
  for (const auto& c : cases) {
    WriteText(tmp.path() / ".zarray", c.body);
    absl::StatusOr<ZarrArray> a = ZarrArray::Open(tmp.path());
    EXPECT_EQ(a.status().code(), absl::StatusCode::kInvalidArgument) << c.body;
    EXPECT_THAT(a.status().message(), AllOf(HasSubstr(".zarray"), HasSubstr(c.field))) << c.body;
  }
}

TEST(ZarrErrorsTest, InvalidSpecsAreRejectedNamingTheField) {
  TempDir tmp;
  const struct {
    ArraySpec spec;
    std::string field;
  } cases[] = {
      {{.shape = {}, .chunks = {}}, "shape"},
      {{.shape = {4}, .chunks = {4, 4}}, "chunks"},
      {{.shape = {4}, .chunks = {0}}, "chunks"},
      {{.shape = {-1}, .chunks = {4}}, "shape"},
      {{.shape = {4}, .chunks = {int64_t{1} << 40}}, "chunks"},
      {{.shape = {4}, .chunks = {4}, .dtype = DType::kUint8, .fill_value = 256}, "fill_value"},
      {{.shape = {4}, .chunks = {4}, .dtype = DType::kInt32, .fill_value = 0.5}, "fill_value"},
      {{.shape = {4}, .chunks = {4}, .zstd_level = 40}, "level"},
      {{.shape = {4}, .chunks = {4}, .dtype = DType::kFloat32, .delta_filter = true}, "filters"},
  };
  for (const auto& c : cases) {
    absl::StatusOr<ZarrArray> a = ZarrArray::Create(tmp.path() / "a", c.spec);
    EXPECT_EQ(a.status().code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_THAT(a.status().message(), HasSubstr(c.field));
  }
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "a"));  // nothing half-made
}

TEST(ZarrErrorsTest, WrongTypeSizeOrChunkIndex) {
  TempDir tmp;
  absl::StatusOr<ZarrArray> a =
      ZarrArray::Create(tmp.path(), {.shape = {10, 6}, .chunks = {4, 4}, .dtype = DType::kFloat32});
  ASSERT_TRUE(a.ok());
  absl::StatusOr<std::vector<uint32_t>> wrong_type =
      a->ReadAll<uint32_t>();  // same size, other type
  EXPECT_EQ(wrong_type.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(wrong_type.status().message(), AllOf(HasSubstr("<f4"), HasSubstr("<u4")));
  EXPECT_EQ(a->ReadChunk<int16_t>(std::vector<int64_t>{0, 0}).status().code(),
            absl::StatusCode::kInvalidArgument);

  // An edge chunk must still be written at full chunk size.
  absl::Status s = a->WriteChunk<float>(std::vector<int64_t>{2, 1}, std::vector<float>(2 * 2));
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), AllOf(HasSubstr("2.1"), HasSubstr("64")));
  s = a->WriteAll<float>(std::vector<float>(59));
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("240"));

  for (std::vector<int64_t> bad : {std::vector<int64_t>{3, 0}, {0, 2}, {-1, 0}, {0}, {0, 0, 0}}) {
    s = a->WriteChunk<float>(bad, std::vector<float>(16));
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(s.message(), HasSubstr("chunk index"));
    EXPECT_EQ(a->ReadChunk(bad).status().code(), absl::StatusCode::kInvalidArgument);
  }
}

TEST(ZarrErrorsTest, AttributesMustBeAnObject) {
  TempDir tmp;
  ASSERT_TRUE(WriteGroup(tmp.path()).ok());
  absl::Status s = WriteAttrs(tmp.path(), nlohmann::json::array({1, 2}));
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr(".zattrs"));
  EXPECT_EQ(*ReadAttrs(tmp.path()), nlohmann::json::object());  // none yet: empty, as in Zarr
  WriteText(tmp.path() / ".zattrs", "[1, 2]");
  EXPECT_EQ(ReadAttrs(tmp.path()).status().code(), absl::StatusCode::kInvalidArgument);
  WriteText(tmp.path() / ".zattrs", "{broken");
  EXPECT_THAT(ReadAttrs(tmp.path()).status().message(), HasSubstr(".zattrs"));
  EXPECT_TRUE(absl::IsNotFound(ReadAttrs(tmp.path() / "missing").status()));
}

}  // namespace
}  // namespace wavebake
