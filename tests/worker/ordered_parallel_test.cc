// OrderedParallel: items produced on several threads are consumed in order,
// never more than `window` ahead, and the first error stops the rest.
#include "worker/loop/ordered_parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace wavebake {
namespace {

TEST(OrderedParallelTest, ConsumesEveryItemInOrderWhateverTheThreads) {
  for (int threads : {1, 2, 5}) {
    std::vector<int> seen;
    const absl::Status s = OrderedParallel<int>(
        50, threads, 3,
        [](int i) -> absl::StatusOr<int> {
          // Later items finish first: the order must come from the consumer.
          std::this_thread::sleep_for(std::chrono::microseconds((50 - i) * 20));
          return i * i;
        },
        [&](int i, int& v) {
          EXPECT_EQ(v, i * i);
          seen.push_back(i);
          return absl::OkStatus();
        });
    ASSERT_TRUE(s.ok()) << s;
    std::vector<int> expected(50);
    for (int i = 0; i < 50; ++i) expected[i] = i;
    EXPECT_EQ(seen, expected) << threads << " threads";
  }
}

TEST(OrderedParallelTest, NeverProducesMoreThanTheWindowAheadOfTheConsumer) {
  std::atomic<int> consumed{0}, worst{0};
  const absl::Status s = OrderedParallel<int>(
      40, 4, 3,
      [&](int i) -> absl::StatusOr<int> {
        int ahead = i - consumed.load();
        int w = worst.load();
        while (ahead > w && !worst.compare_exchange_weak(w, ahead)) {
        }
        return i;
      },
      [&](int, int&) {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        ++consumed;
        return absl::OkStatus();
      });
  ASSERT_TRUE(s.ok()) << s;
  EXPECT_LT(worst.load(), 3);  // item i starts only once i − 3 has been consumed
  EXPECT_EQ(consumed.load(), 40);
}

TEST(OrderedParallelTest, TheFirstErrorStopsTheRestAndIsReturned) {
  std::atomic<int> produced{0};
  int consumed = 0;
  const absl::Status s = OrderedParallel<int>(
      1000, 2, 4,
      [&](int i) -> absl::StatusOr<int> {
        ++produced;
        if (i == 7) return absl::DataLossError("item 7");
        return i;
      },
      [&](int, int&) {
        ++consumed;
        return absl::OkStatus();
      });
  EXPECT_EQ(s.code(), absl::StatusCode::kDataLoss);
  EXPECT_EQ(s.message(), "item 7");
  EXPECT_EQ(consumed, 7);                     // 0..6, in order, then the error
  EXPECT_LT(produced.load(), 7 + 4 + 2 + 1);  // nothing started past the window
}

TEST(OrderedParallelTest, AConsumerErrorIsReturnedToo) {
  const absl::Status s = OrderedParallel<int>(
      100, 3, 2, [](int i) -> absl::StatusOr<int> { return i; },
      [](int i, int&) {
        return i == 10 ? absl::ResourceExhaustedError("disk full") : absl::OkStatus();
      });
  EXPECT_EQ(s.code(), absl::StatusCode::kResourceExhausted);
}

}  // namespace
}  // namespace wavebake
