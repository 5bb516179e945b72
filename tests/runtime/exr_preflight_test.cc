// CheckExrHeaders (runtime/io/exr_preflight.h): what OpenEXR would allocate for
// a header is refused unless the file holds it — the fuzzer's 1.7 GB
// attribute, a preview bomb, a data window no file this size can fill —
// while every file OpenEXR writes passes.
#include "runtime/io/exr_preflight.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>

#include "env_test_util.h"
#include "runtime/io/image_io.h"
#include "storage/files/atomic_file.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

std::string Int(int32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }

// magic, version 2, the attributes given, the empty name.
std::string Header(const std::string& attributes) {
  return std::string("\x76\x2f\x31\x01", 4) + Int(2) + attributes + std::string(1, '\0');
}
std::string Attribute(const std::string& name, const std::string& type, const std::string& value,
                      int32_t size = -1) {
  return name + '\0' + type + '\0' + Int(size >= 0 ? size : int32_t(value.size())) + value;
}
std::string Box(int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
  return Int(x0) + Int(y0) + Int(x1) + Int(y1);
}
absl::Status Check(const std::string& file) {
  return CheckExrHeaders(std::as_bytes(std::span(file)), "h.exr");
}

TEST(ExrPreflightTest, FilesOpenExrWritesPass) {
  for (auto [w, h] : {std::pair{1, 1}, {64, 32}, {300, 7}}) {
    const auto path = testing::ScratchDir() / "ok.exr";
    ASSERT_TRUE(WriteExr(path, w, h, std::vector<float>(size_t(w) * h * 3, 0.5f)).ok());
    absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(path);
    ASSERT_TRUE(bytes.ok());
    EXPECT_TRUE(CheckExrHeaders(*bytes, "ok.exr").ok()) << CheckExrHeaders(*bytes, "ok.exr");
  }
}

TEST(ExrPreflightTest, AValueLargerThanTheFileIsRefused) {
  const std::string bomb = Header(Attribute("x", "weird", "", 0x6e6e6e6e));
  EXPECT_THAT(Check(bomb).message(), HasSubstr("h.exr: unreadable EXR: attribute 'x' claims"));
  EXPECT_FALSE(DecodeExr(std::as_bytes(std::span(bomb)), "h.exr").ok());
}

TEST(ExrPreflightTest, KnownTypesMustHaveTheirOwnSize) {
  EXPECT_THAT(Check(Header(Attribute("dataWindow", "box2i", Box(0, 0, 3, 3) + "junk"))).message(),
              HasSubstr("of type box2i has size 20, not 16"));
  EXPECT_TRUE(Check(Header(Attribute("dataWindow", "box2i", Box(0, 0, 3, 3)))).ok());
}

TEST(ExrPreflightTest, APreviewMustBeItsSize) {
  const std::string preview = Int(40000) + Int(40000);  // 6.4 GB of RGBA promised in 8 bytes
  EXPECT_THAT(Check(Header(Attribute("preview", "preview", preview))).message(),
              HasSubstr("a preview image that is not its size"));
}

TEST(ExrPreflightTest, ADataWindowTheFileCannotFillIsRefused) {
  const std::string huge = Header(Attribute("dataWindow", "box2i", Box(0, 0, 99999, 99999)));
  EXPECT_THAT(Check(huge).message(), HasSubstr("data window of 100000x100000 pixels"));
  EXPECT_THAT(Check(Header(Attribute("dataWindow", "box2i", Box(5, 0, 0, 0)))).message(),
              HasSubstr("data window of -4x1"));
  EXPECT_EQ(ExrPixelLimit(10), int64_t{1} << 20);
  EXPECT_EQ(ExrPixelLimit(size_t{1} << 30), int64_t{1} << 27);
}

TEST(ExrPreflightTest, ChannelListsAreWalkedExactly) {
  const std::string channel = std::string("R\0", 2) + std::string(16, '\0');
  EXPECT_TRUE(Check(Header(Attribute("channels", "chlist", channel + '\0'))).ok());
  EXPECT_THAT(Check(Header(Attribute("channels", "chlist", channel + '\0' + "xy"))).message(),
              HasSubstr("is not its declared size"));
  EXPECT_THAT(Check(Header(Attribute("channels", "chlist", std::string("R\0\0\0", 4)))).message(),
              HasSubstr("cut short"));
}

TEST(ExrPreflightTest, TruncatedHeadersAreRefused) {
  const std::string whole = Header(Attribute("dataWindow", "box2i", Box(0, 0, 3, 3)));
  for (size_t n = 0; n + 1 < whole.size(); ++n) EXPECT_FALSE(Check(whole.substr(0, n)).ok()) << n;
}

}  // namespace
}  // namespace wavebake
