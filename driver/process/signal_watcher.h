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
  // Stops watching at once (the thread is woken, not polled); the signals
  // stay blocked.
  ~SignalWatcher();

 private:
  sigset_t set_;
  // The thread waits on both: the signals, read as data (signalfd), and a
  // wake-up the destructor writes (eventfd).
  int signal_fd_ = -1, stop_fd_ = -1;
  std::jthread thread_;
};

}  // namespace wavebake::driver
