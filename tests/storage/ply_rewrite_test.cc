// The PLY check and rewrite: the three encodings of one mesh give the same
// ASCII text (written out here by hand), and each way a file can lie about
// itself is refused, naming where.
#include "storage/scene_files/ply_rewrite.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstring>

namespace wavebake {
namespace {

using ::testing::HasSubstr;

const std::string kHeader =
    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

// What every encoding of the triangle below rewrites to. Its first x has
// the float bits 0x3f80000a, whose little-endian first byte is '\n', which
// assimp's reader would skip as one more line end after end_header.
const std::string kRewritten =
    "ply\nformat ascii 1.0\n" + kHeader + "1.0000012 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

std::string Binary(bool big) {
  std::string out = std::string("ply\nformat binary_") + (big ? "big" : "little") +
                    "_endian 1.0\ncomment three encodings\n" + kHeader;
  const auto put = [&](uint32_t u, int bytes) {
    for (int k = 0; k < bytes; ++k)
      out.push_back(static_cast<char>(u >> (8 * (big ? bytes - 1 - k : k))));
  };
  for (float f : {std::bit_cast<float>(0x3f80000au), 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
    put(std::bit_cast<uint32_t>(f), 4);
  put(3, 1);
  for (uint32_t i : {0u, 1u, 2u}) put(i, 4);
  return out;
}

TEST(PlyRewriteTest, AsciiAndBothBinaryEncodingsRewriteToTheSameText) {
  const std::string ascii =
      "ply\r\nformat ascii 1.0\r\n" + kHeader + "1.0000012 0 0\n1\t0  0\r\n0 1 0\n3 0 1 2\n\n";
  for (const std::string& file : {ascii, Binary(false), Binary(true)}) {
    absl::StatusOr<std::string> text = RewritePly(file);
    ASSERT_TRUE(text.ok()) << text.status();
    EXPECT_EQ(*text, kRewritten);
  }
}

TEST(PlyRewriteTest, KeepsVertexPropertiesAndDropsFaceScalars) {
  const std::string file =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nproperty float32 s\nproperty float32 t\nelement face 1\n"
      "property uchar red\nproperty list uint8 uint vertex_index\nend_header\n"
      "0 0 0 0.25 0.5\n1 0 0 1 0.5\n0 1 0 0 1\n200 3 2 1 0\n";
  absl::StatusOr<std::string> text = RewritePly(file);
  ASSERT_TRUE(text.ok()) << text.status();
  EXPECT_EQ(*text,
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nproperty float s\nproperty float t\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n"
            "0 0 0 0.25 0.5\n1 0 0 1 0.5\n0 1 0 0 1\n3 2 1 0\n");
}

// Every float is written as a float in its shortest form: a double with 17
// digits would print as 21 fixed digits, which assimp's 64-bit integer-part
// parser wraps. A trailing space after end_header is still the header's end.
TEST(PlyRewriteTest, LargeDoublesAreWrittenInAFormAssimpReads) {
  const std::string file =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header \n"
      "1.2345678901234567e20 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  absl::StatusOr<std::string> text = RewritePly(file);
  ASSERT_TRUE(text.ok()) << text.status();
  EXPECT_EQ(text->substr(text->find("end_header\n") + 11),
            "1.2345679e+20 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
}

TEST(PlyRewriteTest, EachLieIsRefusedNamingWhere) {
  const std::string a = "ply\nformat ascii 1.0\n";
  const std::string v = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string f = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n";
  const std::pair<std::string, std::string> cases[] = {
      {a + v, "without its end_header"},
      {"ply?\nformat ascii 1.0\n" + v + f + body + "3 0 1 2\n", "line 1 is not 'ply'"},
      {"ply\nformat ascii 2.0\n" + v + f + body + "3 0 1 2\n", "line 2: not a format line"},
      {a + v + v + f + body + "3 0 1 2\n", "line 7: not the one vertex or face element"},
      {a + "element edge 1\nproperty int a\n" + v + f, "line 3: not the one vertex"},
      {a + "element vertex z\n" + f, "element count 'z' is not a number"},
      {a + "property float x\n" + v + f, "line 3: a property before elements"},
      {a + v + "property ucat w\n" + f, "line 7: unknown type 'ucat'"},
      {a + v + "property float x\n" + f, "line 7: property 'x' twice"},
      {a + v + "property list uchar int n\n" + f, "list property 'n' of element 'vertex'"},
      {a + v + f.substr(0, 15) +
           "property list uchar int vertex_indices\n"
           "property list uchar float texcoord\nend_header\n",
       "list property 'texcoord' of element 'face'"},
      {a + v + f.substr(0, 15) + "property list float int vertex_indices\nend_header\n",
       "needs integer types"},
      {a + v + "element face 1\nproperty int flags\nend_header\n", "without a face element"},
      {a + "element vertex 3\nproperty float x\nproperty float z\n" + f, "without property 'y'"},
      {a + v + "bogus\n" + f, "line 7: not a header keyword"},
      {a + v + f + body, "PLY ends at face 0 of 1"},
      {a + v + f + body + "3 0 1 3\n", "PLY face 0: vertex index 3 of 3 vertices"},
      {a + v + f + body + "3 0 1 -1\n", "vertex index -1 of 3"},
      {a + v + f + body + "2 0 1\n", "PLY face 0: a face of 2 indices (3 to 255 are read)"},
      {a + v + f + body + "3 0 1\n",
       "PLY face 0: property 'vertex_indices': its line has too few values"},
      {a + v + f + body + "3 0 1 2 0\n",
       "PLY face 0: its line has more values than its properties"},
      {a + v + f + body + "3 0 1 2\n3 0 1 2\n", "lines after its last face"},
      {a + v + f + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "vertex 1: property 'y': a value that"},
      {a + v + f + "0 0 0\n1 1e99 0\n0 1 0\n3 0 1 2\n", "vertex 1: property 'y': a value that"},
      {a + v + f + "0 0 0\n1 0x1 0\n0 1 0\n3 0 1 2\n",
       "vertex 1: property 'y': '0x1' is not a valid float"},
      {a + v + f + body + "3 0 1 2.5\n", "'2.5' is not a valid int"},
      {a + v + f + body + "256 0 1 2\n", "value 256 does not fit in a uchar"},
      {Binary(false).substr(0, Binary(false).size() - 1),
       "PLY face 0: property 'vertex_indices': the file ends inside it"},
      {Binary(true) + "x", "PLY with 1 bytes after its last face"},
      // A name is written back into the header assimp reads, which takes
      // '\r' for a line end: this one would declare a second vertex element.
      {a + v + "property float a\relement\tvertex\t100000\rproperty\tfloat\tw\n" + f,
       "line 7: property name 'a\\relement"},
      {a + "element face 1\nproperty list uchar int vertex_indices\n" + v + "end_header\n",
       "line 3: the face element before the vertex element"},
      {a + "element vertex\n" + f, "line 3: a malformed element line"},
      {a + v + "comment " + std::string(2000, 'c') + "\n" + f, "line 7: longer than 1024 bytes"},
      {a + v + std::string(1100, 'x') + "\n" + f, "line 7: longer than 1024 bytes"},
      {a + v + f.substr(0, 15) + "property list uchar uchar vertex_indices\nend_header\n" + body +
           "3 0 1 44\n",
       "vertex index 44 of 3"},
      {a + v + f.substr(0, 15) + "property list uchar uchar vertex_indices\nend_header\n" + body +
           "3 0 1 299\n",
       "value 299 does not fit in a uchar"},
      {a + v + "element face 0\nproperty list uchar int vertex_indices\nend_header\n" + body,
       "PLY without a face element, its index list and a face"},
      {a + "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n" + f +
           "0 0 0\n1 0 0\n0 1e39 0\n3 0 1 2\n",
       "vertex 2: property 'y': a value that is not a finite float"},
      {a + v + f.substr(0, f.size() - 1), "PLY ends at vertex 0 of 3"},  // no newline after it
  };
  std::string many = a + v;
  for (int k = 0; k < 62; ++k) many += "property uchar p" + std::to_string(k) + "\n";
  const absl::StatusOr<std::string> wide = RewritePly(many + f);
  EXPECT_THAT(wide.status().message(), HasSubstr("line 68: more than 64 properties of element"));
  for (const auto& [file, message] : cases) {
    const absl::StatusOr<std::string> text = RewritePly(file);
    ASSERT_FALSE(text.ok()) << file;
    EXPECT_EQ(text.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(text.status().message(), HasSubstr(message)) << file;
  }
}

// A count far beyond the file is refused when the file ends, after reading
// no more than the file: nothing is sized by what the header says.
TEST(PlyRewriteTest, AHugeCountEndsWithTheFile) {
  const std::string file =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n" +
      std::string(24, '\0');
  EXPECT_THAT(RewritePly(file).status().message(), HasSubstr("PLY ends at vertex 2 of 2000000000"));
  EXPECT_THAT(RewritePly("ply\nformat ascii 1.0\nelement vertex 3000000000\n").status().message(),
              HasSubstr("end_header"));
}

}  // namespace
}  // namespace wavebake
