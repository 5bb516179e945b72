#include "driver/process/signal_watcher.h"

#include <pthread.h>

#include <ctime>

namespace wavebake::driver {

SignalWatcher::SignalWatcher(std::function<void(int)> on_signal) {
  sigemptyset(&set_);
  sigaddset(&set_, SIGINT);
  sigaddset(&set_, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set_, nullptr);
  thread_ = std::jthread([this, on_signal = std::move(on_signal)](std::stop_token stop) {
    // Polls the stop request a few times a second (sigwait cannot be woken).
    const timespec tick{0, 200'000'000};
    while (!stop.stop_requested()) {
      const int signo = sigtimedwait(&set_, nullptr, &tick);
      if (signo > 0) on_signal(signo);
    }
  });
}

SignalWatcher::~SignalWatcher() {
  thread_.request_stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace wavebake::driver
