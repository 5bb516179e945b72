// The parallel loops visit every index once, whatever the thread count, and
// ParallelTasks stops at the first failure and returns it.
#include "core/util/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

class ParallelTasksThreads : public ::testing::TestWithParam<int> {};

TEST_P(ParallelTasksThreads, EveryTaskRunsOnce) {
  std::vector<std::atomic<int>> runs(1000);
  const absl::Status s = ParallelTasks(1000, GetParam(), [&](int i) {
    ++runs[i];
    return absl::OkStatus();
  });
  EXPECT_TRUE(s.ok()) << s;
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(runs[i].load(), 1) << i;
}

TEST_P(ParallelTasksThreads, TheFirstFailureIsReturnedAndNoNewTaskStarts) {
  std::atomic<int> started{0};
  const absl::Status s = ParallelTasks(1000, GetParam(), [&](int i) {
    ++started;
    if (i == 10) return absl::DataLossError(absl::StrCat("task ", i));
    if (i > 10) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return absl::OkStatus();
  });
  EXPECT_TRUE(absl::IsDataLoss(s)) << s;
  EXPECT_EQ(s.message(), "task 10");
  // Tasks 0..10 and the few others already running: not the ~1 s of all.
  EXPECT_LT(started.load(), 100);
}

// 0 and negative thread counts mean the caller's thread alone.
INSTANTIATE_TEST_SUITE_P(Threads, ParallelTasksThreads, ::testing::Values(-1, 0, 1, 2, 4));

TEST(ParallelForWorkers, EveryIndexOnceAndWorkersInRange) {
  std::vector<std::atomic<int>> runs(777);
  std::atomic<bool> worker_out_of_range{false};
  ParallelForWorkers(777, 3, 10, [&](int worker, int i) {
    if (worker < 0 || worker >= 3) worker_out_of_range = true;
    ++runs[i];
  });
  EXPECT_FALSE(worker_out_of_range);
  for (int i = 0; i < 777; ++i) EXPECT_EQ(runs[i].load(), 1) << i;
}

}  // namespace
}  // namespace wavebake
