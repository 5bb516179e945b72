#pragma once
// Every wait has a bound, shutdown's too. A gRPC server's Shutdown waits for
// every running call to return, and a call busy in a long CPU step (a
// scene's post-processing in the planner) cannot be interrupted; without a
// bound, SIGTERM would leave the process stopped but alive for as long as
// that step takes. Armed once shutdown begins: if the holder has not
// disarmed it (destroyed it) within `bound`, the process logs why and exits
// at once with `exit_code`, without running destructors — the coordinator
// commits every transition as it happens, so nothing is lost but the call
// that was still running, whose client sees its connection end.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace wavebake::driver {

class ExitDeadline {
 public:
  ExitDeadline(std::chrono::milliseconds bound, std::string what, int exit_code);
  ExitDeadline(const ExitDeadline&) = delete;
  ExitDeadline& operator=(const ExitDeadline&) = delete;
  ~ExitDeadline();  // disarms it

 private:
  std::mutex mu_;
  std::condition_variable_any cv_;
  std::jthread thread_;
};

}  // namespace wavebake::driver
