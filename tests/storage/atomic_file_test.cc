#include "storage/files/atomic_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/storage/test_support.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using testing::PartialFiles;
using testing::TempDir;

std::vector<std::byte> Bytes(const std::string& s) {
  const auto b = std::as_bytes(std::span(s));
  return {b.begin(), b.end()};
}

// Reads with plain stdio, not with the ReadFile under test.
std::string Slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(AtomicFileTest, WritesReplacesAndReadsBack) {
  TempDir tmp;
  const auto path = tmp.path() / "f.bin";
  ASSERT_TRUE(AtomicWriteFile(path, Bytes("first version")).ok());
  EXPECT_EQ(Slurp(path), "first version");
  ASSERT_TRUE(AtomicWriteFile(path, Bytes("v2")).ok());
  EXPECT_EQ(Slurp(path), "v2");
  absl::StatusOr<std::vector<std::byte>> read = ReadFile(path);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(*read, Bytes("v2"));
  ASSERT_TRUE(AtomicWriteFile(path, {}).ok());
  EXPECT_EQ(std::filesystem::file_size(path), 0u);
  EXPECT_THAT(PartialFiles(tmp.path()), IsEmpty());
}

// A file written in parts is their concatenation, empty parts included.
TEST(AtomicFileTest, PartsAreWrittenInOrder) {
  TempDir tmp;
  const auto path = tmp.path() / "parts.bin";
  const std::vector<std::byte> a = Bytes("head:"), b = Bytes(""),
                               c = Bytes(std::string(70000, 'x'));
  const std::span<const std::byte> parts[] = {a, b, c, a};
  ASSERT_TRUE(AtomicWriteFileParts(path, parts).ok());
  EXPECT_EQ(Slurp(path), "head:" + std::string(70000, 'x') + "head:");
  EXPECT_THAT(PartialFiles(tmp.path()), IsEmpty());
}

// A range inside the file reads exactly those bytes; one reaching past the
// end is OutOfRange naming the file; a missing file is NotFound.
TEST(AtomicFileTest, ReadFileRangeReadsExactlyTheRange) {
  TempDir tmp;
  const auto path = tmp.path() / "range.bin";
  ASSERT_TRUE(AtomicWriteFile(path, Bytes("0123456789")).ok());
  ByteBuffer buf;
  ASSERT_TRUE(ReadFileRangeInto(path, 3, 4, buf).ok());
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(buf.data()), buf.size()), "3456");
  ASSERT_TRUE(ReadFileRangeInto(path, 10, 0, buf).ok());
  EXPECT_TRUE(buf.empty());
  const absl::Status past = ReadFileRangeInto(path, 8, 3, buf);
  EXPECT_TRUE(absl::IsOutOfRange(past)) << past;
  EXPECT_THAT(past.message(), HasSubstr("range.bin"));
  EXPECT_TRUE(absl::IsNotFound(ReadFileRangeInto(tmp.path() / "nope", 0, 1, buf)));
}

TEST(AtomicFileTest, MissingFileIsNotFoundNamingThePath) {
  TempDir tmp;
  absl::StatusOr<std::vector<std::byte>> read = ReadFile(tmp.path() / "nope");
  EXPECT_TRUE(absl::IsNotFound(read.status()));
  EXPECT_THAT(read.status().message(), HasSubstr("nope"));
}

// A buffer reused from file to file (the chunk reads' per-thread buffer)
// holds exactly the file read last: a shorter file after a longer one leaves
// nothing of the longer one, and a missing file is NotFound as for ReadFile.
TEST(AtomicFileTest, ReadFileIntoAReusedBufferHoldsExactlyTheLastFile) {
  TempDir tmp;
  const std::string longer(70000, 'L'), shorter = "short";
  ASSERT_TRUE(AtomicWriteFile(tmp.path() / "long", Bytes(longer)).ok());
  ASSERT_TRUE(AtomicWriteFile(tmp.path() / "short", Bytes(shorter)).ok());
  ByteBuffer buffer;
  for (const auto& [name, content] :
       {std::pair{"long", longer}, std::pair{"short", shorter}, std::pair{"long", longer}}) {
    ASSERT_TRUE(ReadFileInto(tmp.path() / name, buffer).ok());
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(buffer.data()), buffer.size()), content)
        << name;
  }
  const absl::Status missing = ReadFileInto(tmp.path() / "nope", buffer);
  EXPECT_TRUE(absl::IsNotFound(missing));
  EXPECT_THAT(missing.message(), HasSubstr("nope"));
}

TEST(AtomicFileTest, FailedWriteLeavesNoTempFileAndKeepsTarget) {
  TempDir tmp;
  // Missing directory: the temp file cannot even be created.
  absl::Status s = AtomicWriteFile(tmp.path() / "no_dir" / "f", Bytes("x"));
  EXPECT_FALSE(s.ok());
  EXPECT_THAT(s.message(), HasSubstr("no_dir"));
  // Target is a non-empty directory: the temp file is written, the rename fails.
  std::filesystem::create_directories(tmp.path() / "d" / "inner");
  s = AtomicWriteFile(tmp.path() / "d", Bytes("x"));
  EXPECT_FALSE(s.ok());
  EXPECT_THAT(s.message(), HasSubstr("rename"));
  EXPECT_TRUE(std::filesystem::is_directory(tmp.path() / "d" / "inner"));
  EXPECT_THAT(PartialFiles(tmp.path()), IsEmpty());
}

// Many threads replacing one file (retried tasks rewriting a chunk): every
// read sees one writer's complete contents, and no temp file survives.
TEST(AtomicFileTest, ConcurrentReplacementsAreNeverTorn) {
  TempDir tmp;
  const auto path = tmp.path() / "shared";
  constexpr int kThreads = 6, kRounds = 40;
  auto content = [](int t) { return std::string(20000 + 1000 * t, static_cast<char>('a' + t)); };
  ASSERT_TRUE(AtomicWriteFile(path, Bytes(content(0))).ok());
  std::vector<std::thread> threads;
  std::vector<int> torn(kThreads, 0), failed(kThreads, 0);
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int r = 0; r < kRounds; ++r) {
        failed[t] += !AtomicWriteFile(path, Bytes(content(t))).ok();
        const std::string seen = Slurp(path);
        const int who = seen.empty() ? -1 : seen[0] - 'a';
        torn[t] += who < 0 || who >= kThreads || seen != content(who);
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) {
    EXPECT_EQ(failed[t], 0) << "thread " << t;
    EXPECT_EQ(torn[t], 0) << "thread " << t;
  }
  EXPECT_THAT(PartialFiles(tmp.path()), IsEmpty());
}

// A writer killed between write and rename leaves ".NAME.PID.HEX.partial";
// only such names go, at any depth, and a user's look-alikes stay.
TEST(AtomicFileTest, RemovesOnlyAbandonedTempFiles) {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "transport" / "data");
  const std::vector<std::filesystem::path> abandoned = {
      dir.path() / "..zgroup.32280.02f48aabfca56c68.partial",
      dir.path() / "transport" / "data" / ".0.7.ffffffffffffffff.partial"};
  const std::vector<std::filesystem::path> kept = {
      dir.path() / ".zgroup", dir.path() / "notes.partial", dir.path() / ".draft.partial",
      dir.path() / ".x.1.0123456789abcdeg.partial", dir.path() / "transport" / "data" / "0"};
  for (const auto& p : abandoned) std::ofstream(p) << "torn";
  for (const auto& p : kept) std::ofstream(p) << "mine";
  ASSERT_TRUE(RemoveAbandonedTempFiles(dir.path()).ok());
  for (const auto& p : abandoned) EXPECT_FALSE(std::filesystem::exists(p)) << p;
  for (const auto& p : kept) EXPECT_EQ(Slurp(p), "mine") << p;
}

}  // namespace
}  // namespace wavebake
