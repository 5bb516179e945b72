// The bake's tiles write staging chunks in parallel from threads and worker
// processes (DESIGN.md §2, §4), and retried tasks rewrite chunks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <thread>

#include "storage/zarr/chunk_region.h"
#include "storage/zarr/zarr_array.h"
#include "tests/storage/array_values.h"
#include "tests/storage/test_support.h"

namespace wavebake {
namespace {

using ::testing::IsEmpty;
using testing::PartialFiles;
using testing::TempDir;
using testing::TestValues;

// A staging-like array: [M, S] float, chunked [column_group, tile], with partial edges.
const ArraySpec kSpec{.shape = {100, 90}, .chunks = {16, 16}, .dtype = DType::kFloat32};

// Writes the chunks with index k % stride == offset from `values` (the whole
// array), plus chunk (0, 0) every time, as a retried task would.
absl::Status WriteShare(const ZarrArray& array, std::span<const float> values, size_t offset,
                        size_t stride) {
  const std::vector<std::vector<int64_t>> all = AllChunkIndices(array.spec());
  std::vector<std::byte> chunk(array.chunk_bytes());
  for (size_t k = 0; k < all.size(); ++k) {
    if (k % stride != offset && k != 0) continue;
    FillElements(DType::kFloat32, 0, chunk);
    CopyArrayToChunk(array.spec(), all[k], std::as_bytes(values), chunk);
    if (absl::Status s = array.WriteChunk(all[k], chunk); !s.ok()) return s;
  }
  return absl::OkStatus();
}

void ExpectArrayIs(const std::filesystem::path& dir, const std::vector<float>& values) {
  absl::StatusOr<ZarrArray> reopened = ZarrArray::Open(dir);
  ASSERT_TRUE(reopened.ok()) << reopened.status();
  absl::StatusOr<std::vector<float>> back = reopened->ReadAll<float>();
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_TRUE(testing::BitEqual<float>(*back, values));
  EXPECT_THAT(PartialFiles(dir), IsEmpty());
  EXPECT_EQ(AllChunkIndices(kSpec).size(), 7u * 6u);
}

TEST(ConcurrentWritesTest, ThreadsWritingDistinctChunks) {
  TempDir tmp;
  absl::StatusOr<ZarrArray> array = ZarrArray::Create(tmp.path(), kSpec);
  ASSERT_TRUE(array.ok());
  const std::vector<float> values = TestValues<float>(ElementCount(kSpec), 21);
  constexpr size_t kThreads = 8;
  std::vector<absl::Status> results(kThreads);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] { results[t] = WriteShare(*array, values, t, kThreads); });
  }
  for (auto& th : threads) th.join();
  for (const absl::Status& s : results) EXPECT_TRUE(s.ok()) << s;
  ExpectArrayIs(tmp.path(), values);
}

TEST(ConcurrentWritesTest, ProcessesWritingDistinctChunks) {
  TempDir tmp;
  const std::vector<float> values = TestValues<float>(ElementCount(kSpec), 22);
  constexpr size_t kProcesses = 3;
  std::vector<pid_t> children;
  for (size_t p = 0; p < kProcesses; ++p) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      // Every worker process creates (opens) the array itself, as workers do.
      absl::StatusOr<ZarrArray> array = ZarrArray::Create(tmp.path(), kSpec);
      ::_exit(array.ok() && WriteShare(*array, values, p, kProcesses).ok() ? 0 : 1);
    }
    children.push_back(pid);
  }
  for (pid_t pid : children) {
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  ExpectArrayIs(tmp.path(), values);
}

}  // namespace
}  // namespace wavebake
