#pragma once
// SIGINT and SIGTERM for the long-running commands (`coordinator` shuts down,
// `worker` drains, `bake` cancels its job): the signals are blocked and a
// thread of ours waits for them, so the reaction runs as ordinary code, not
// in a signal handler. Create it before any other thread (gRPC's included):
// threads inherit the blocked mask.
#include <csignal>
#include <functional>
#include <thread>

namespace wavebake::driver {

class SignalWatcher {
 public:
  // on_signal(signo) runs on the watcher's thread, once per signal received.
  explicit SignalWatcher(std::function<void(int)> on_signal);
  SignalWatcher(const SignalWatcher&) = delete;
  SignalWatcher& operator=(const SignalWatcher&) = delete;
  ~SignalWatcher();  // stops watching; the signals stay blocked

 private:
  sigset_t set_;
  std::jthread thread_;
};

}  // namespace wavebake::driver
