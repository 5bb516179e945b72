// SignalWatcher (driver/process/signal_watcher.h): SIGINT and SIGTERM sent to
// the process reach on_signal on the watcher's thread, each with its number,
// and its destructor ends the watch without waiting for a signal.
#include "driver/process/signal_watcher.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <vector>

namespace wavebake::driver {
namespace {

TEST(SignalWatcherTest, SignalsReachTheCallbackWithTheirNumbers) {
  std::mutex mu;
  std::condition_variable seen;
  std::vector<int> got;
  {
    SignalWatcher watcher([&](int signo) {
      std::lock_guard lock(mu);
      got.push_back(signo);
      seen.notify_all();
    });
    for (int signo : {SIGTERM, SIGINT}) {
      std::unique_lock lock(mu);
      const size_t before = got.size();  // before the signal: it may be seen at once
      ASSERT_EQ(kill(getpid(), signo), 0);
      ASSERT_TRUE(
          seen.wait_for(lock, std::chrono::seconds(10), [&] { return got.size() > before; }))
          << "signal " << signo << " not seen";
    }
  }  // the destructor wakes the thread: no signal is pending
  EXPECT_EQ(got, (std::vector<int>{SIGTERM, SIGINT}));
}

}  // namespace
}  // namespace wavebake::driver
