// The OBJ check and rewrite: a file using the relative index forms, tabs,
// CRLF and comments rewrites to the plain text written out here by hand; each
// way a line can be wrong is refused naming the line; a face too large to
// triangulate is refused in time linear in the file.
#include "storage/scene_files/obj_rewrite.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

TEST(ObjRewriteTest, RelativeIndicesBecomeAbsoluteAndNumbersKeepTheirSpelling) {
  const std::string file =
      "# exported\r\n"
      "mtllib two words.mtl\r\n"
      "o thing   # named\r\n"
      "v 1.0e-3\t+2 -3.50\r\n"
      "v 4 5 6 0.5\r\n"
      "v 7 8 9 1 0.5 0\r\n"
      "vt 0.25 0.75\n"
      "vn 0 0 1\n"
      "\n"
      "g a b\n"
      "usemtl mat#2\n"
      "s off\n"
      "f -3/-1/1 2/1/-1 -1/1/1\n"
      "f 1//1 2//1 3//-1\n"
      "f 1/1 -2/1 3/1\n"
      "l 1 -1\n"
      "p -3\n";
  absl::StatusOr<std::string> text = RewriteObj(file);
  ASSERT_TRUE(text.ok()) << text.status();
  EXPECT_EQ(*text,
            "mtllib two words.mtl\n"
            "o thing\n"
            "v 1.0e-3 +2 -3.50\n"
            "v 4 5 6 0.5\n"
            "v 7 8 9 1 0.5 0\n"
            "vt 0.25 0.75\n"
            "vn 0 0 1\n"
            "g a b\n"
            "usemtl mat#2\n"
            "s off\n"
            "f 1/1/1 2/1/1 3/1/1\n"
            "f 1//1 2//1 3//1\n"
            "f 1/1 2/1 3/1\n"
            "l 1 3\n"
            "p 1\n");
}

TEST(ObjRewriteTest, EachWrongLineIsRefusedNamingIt) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::pair<std::string, std::string> cases[] = {
      {tri + "f 1 2 4\n", "OBJ line 4: vertex index 4 of 3 defined above it"},
      {tri + "f 1 2 -4\n", "OBJ line 4: vertex index -4 of 3"},
      {tri + "f 0 1 2\n", "OBJ line 4: vertex index 0 of 3"},
      {"f 1 2 3\n" + tri, "OBJ line 1: vertex index 1 of 0"},
      {tri + "f 1/1 2/1 3/1\n", "OBJ line 4: texture coordinate index 1 of 0"},
      {tri + "vn 0 0 1\nf 1//2 2//1 3//1\n", "OBJ line 5: normal index 2 of 1"},
      {tri + "vt 0 0\nf 1/1 2 3\n", "OBJ line 5: corner '2' is not in the form"},
      {tri + "f 1/ 2/ 3/\n", "OBJ line 4: corner '1/' is not v, v/vt, v//vn or v/vt/vn"},
      {tri + "f 1/1/1/1 2 3\n", "has more than three indices"},
      {tri + "f 1 2 x\n", "OBJ line 4: vertex index 'x' is not an integer"},
      {tri + "f 1 2 99999999999999999999\n", "is not an integer"},
      {tri + "f 1 2\n", "OBJ line 4: 'f' with 2 corners (3 to 255 are read)"},
      {tri + "l 1\n", "OBJ line 4: 'l' with 1 corners (2 to 255 are read)"},
      {"v 0 nan 0\n", "OBJ line 1: 'nan' is not finite"},
      {"v 0 0 inf\n", "'inf' is not finite"},
      {"v 0 0 1e39\n", "'1e39' is not finite (or above 1e38)"},
      {"v 0 0 1e999\n", "'1e999' is not a number"},
      {"v 0x10 0 0\n", "'0x10' is not a number"},
      {"v 1 1 1 0\n", "OBJ line 1: 'v' with w 0"},
      {"v 1e30 1 1 1e-20\n", "x/w, y/w, z/w must be finite"},
      {"v 0 0\n", "OBJ line 1: 'v' with 2 numbers (3, 4 or 6 are read)"},
      {"vt 0\n", "'vt' with 1 numbers (2 or 3 are read)"},
      {"vn 0 0 1 0\n", "'vn' with 4 numbers (3 are read)"},
      {"v 0 0 \\\n0\n", "OBJ line 1: a '\\' line continuation"},
      {"v 0 0 0\r0\n", "OBJ line 1: a control byte (13)"},
      {std::string("v 0 0 0\n\0\n", 10), "OBJ line 2: a control byte (0)"},
      {"curv 0 1 1 2\n", "OBJ line 1: 'curv' statements are not read"},
      {"usemtl\n", "'usemtl' without a name"},
      {"s 1 2\n", "'s' takes one group"},
  };
  for (const auto& [file, want] : cases) {
    const absl::StatusOr<std::string> text = RewriteObj(file);
    ASSERT_FALSE(text.ok()) << file;
    EXPECT_TRUE(absl::IsInvalidArgument(text.status()));
    EXPECT_THAT(text.status().message(), HasSubstr(want)) << file;
  }
}

TEST(ObjRewriteTest, FacesUpTo255CornersPass) {
  std::string file;
  for (int i = 0; i < 255; ++i) file += "v " + std::to_string(i) + " 0 0\n";
  std::string face = "f";
  for (int i = 1; i <= 255; ++i) absl::StrAppend(&face, " ", i);
  absl::StatusOr<std::string> text = RewriteObj(file + face + "\n");
  ASSERT_TRUE(text.ok()) << text.status();
  EXPECT_THAT(*text, HasSubstr(face + "\n"));
  std::string longer = file;  // built in steps: GCC 12 warns (-Wrestrict) on a + b + c here
  longer += face;
  longer += " 1\n";
  EXPECT_THAT(RewriteObj(longer).status().message(), HasSubstr("'f' with more than 255 corners"));
}

// One face line of 3 M indices (6 MB): assimp would triangulate it in time
// quadratic in its corners; the check refuses it, reading it once.
TEST(ObjRewriteTest, AFaceOfThreeMillionCornersIsRefusedAtOnce) {
  std::string file = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  file.reserve(file.size() + 6'000'000);
  for (int i = 0; i < 3'000'000; ++i) file += i % 2 ? " 1" : " 2";
  file += "\n";
  const auto t0 = std::chrono::steady_clock::now();
  const absl::StatusOr<std::string> text = RewriteObj(file);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_FALSE(text.ok());
  EXPECT_THAT(text.status().message(), HasSubstr("OBJ line 4: 'f' with more than 255 corners"));
  EXPECT_LT(seconds, 2.0);
}

}  // namespace
}  // namespace wavebake
