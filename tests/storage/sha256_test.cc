// SHA-256 against the FIPS 180-4 example vectors (an independent anchor),
// fed whole and in pieces, and through a file.
#include "storage/files/sha256.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/storage/test_support.h"

namespace wavebake {
namespace {

constexpr char kAbc[] = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
constexpr char kEmpty[] = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855";
constexpr char kTwoBlocks[] = "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1";
constexpr char kTwoBlocksText[] = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";

TEST(Sha256Test, MatchesTheStandardsExamples) {
  EXPECT_EQ(Sha256Hex("abc"), kAbc);
  EXPECT_EQ(Sha256Hex(""), kEmpty);
  EXPECT_EQ(Sha256Hex(kTwoBlocksText), kTwoBlocks);
}

TEST(Sha256Test, PiecesHashLikeTheWhole) {
  const std::string text = kTwoBlocksText;
  for (size_t cut : {size_t{1}, size_t{7}, size_t{55}}) {
    Sha256 sha;
    sha.Update(std::string_view(text).substr(0, cut));
    sha.Update(std::string_view(text).substr(cut));
    EXPECT_EQ(sha.HexDigest(), kTwoBlocks) << "cut at " << cut;
  }
}

TEST(Sha256Test, HashesAFileAndNamesAMissingOne) {
  testing::TempDir dir;
  const auto path = dir.path() / "abc.txt";
  std::ofstream(path, std::ios::binary) << "abc";
  absl::StatusOr<std::string> got = Sha256OfFile(path);
  ASSERT_TRUE(got.ok()) << got.status();
  EXPECT_EQ(*got, kAbc);
  absl::StatusOr<std::string> missing = Sha256OfFile(dir.path() / "nope");
  EXPECT_FALSE(missing.ok());
  EXPECT_NE(std::string(missing.status().message()).find("nope"), std::string::npos);
}

}  // namespace
}  // namespace wavebake
