// ContextCache: a job's BakeContext is built once per worker, however many of
// its threads ask at once, and shared read-only.
#include "worker/loop/context_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace wavebake {
namespace {

BakeParams Tiny() {
  BakeParams p;
  p.light_res = 8;
  p.layout = "camera:8x8";
  return p;
}

ContextCache::BuildFn Counting(std::atomic<int>& calls, const char* scene = "builtin:furnace") {
  return [&calls, scene] {
    ++calls;
    return MakeBakeContext(scene, Tiny());
  };
}

TEST(ContextCacheTest, ConcurrentCallersShareOneBuild) {
  ContextCache cache;
  std::atomic<int> calls{0};
  const ContextCache::BuildFn build = Counting(calls);
  std::vector<ContextCache::Context> got(8);
  std::vector<std::thread> threads;
  for (size_t i = 0; i < got.size(); ++i) {
    threads.emplace_back([&, i] {
      absl::StatusOr<ContextCache::Context> c = cache.Get("job-1", build);
      if (c.ok()) got[i] = *c;
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(cache.builds(), 1u);
  for (const auto& c : got) {
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(c.get(), got[0].get());
  }
}

TEST(ContextCacheTest, KeepsTheMostRecentlyUsed) {
  ContextCache cache(2);
  std::atomic<int> calls{0};
  const ContextCache::BuildFn build = Counting(calls);
  ASSERT_TRUE(cache.Get("a", build).ok());
  ASSERT_TRUE(cache.Get("b", build).ok());
  ASSERT_TRUE(cache.Get("a", build).ok());  // a is now the most recent
  ASSERT_TRUE(cache.Get("c", build).ok());  // evicts b
  EXPECT_EQ(calls, 3);
  ASSERT_TRUE(cache.Get("a", build).ok());
  EXPECT_EQ(calls, 3);
  ASSERT_TRUE(cache.Get("b", build).ok());  // built again
  EXPECT_EQ(calls, 4);
}

TEST(ContextCacheTest, AFailedBuildIsReportedAndNotKept) {
  ContextCache cache;
  std::atomic<int> calls{0};
  const ContextCache::BuildFn bad = Counting(calls, "builtin:no-such-scene");
  absl::StatusOr<ContextCache::Context> first = cache.Get("job", bad);
  EXPECT_FALSE(first.ok());
  EXPECT_FALSE(cache.Get("job", bad).ok());
  EXPECT_EQ(calls, 2);  // tried again, not served from the cache
  const ContextCache::BuildFn good = Counting(calls);
  EXPECT_TRUE(cache.Get("job", good).ok());
}

}  // namespace
}  // namespace wavebake
