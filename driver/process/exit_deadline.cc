#include "driver/process/exit_deadline.h"

#include <spdlog/spdlog.h>

#include <cstdlib>

namespace wavebake::driver {

ExitDeadline::ExitDeadline(std::chrono::milliseconds bound, std::string what, int exit_code) {
  thread_ = std::jthread([this, bound, what = std::move(what), exit_code](std::stop_token stop) {
    std::unique_lock lock(mu_);
    if (cv_.wait_for(lock, stop, bound, [] { return false; }) || stop.stop_requested()) return;
    spdlog::error("{}: still busy {} ms after shutdown began; exiting without waiting", what,
                  bound.count());
    spdlog::default_logger()->flush();
    std::_Exit(exit_code);
  });
}

ExitDeadline::~ExitDeadline() {
  thread_.request_stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace wavebake::driver
