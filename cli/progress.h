#pragma once
// Progress of long work on stderr: a redrawn bar on a terminal, plain lines
// (at most one every few seconds, and at every phase change) otherwise.
#include <chrono>
#include <cstdint>
#include <string>

namespace wavebake::cli {

struct ProgressState {
  std::string phase;  // e.g. "bake tiles", "transform columns", "finalize"
  int64_t done = 0, total = 0;
  uint64_t rays = 0;  // rays traced so far in the whole job
  // When known better by the caller (a coordinator's live numbers), >= 0
  // replaces the reporter's own estimates from its clock.
  double rays_per_second = -1;
  double eta_seconds = -1;
};

class ProgressReporter {
 public:
  ProgressReporter();
  void Update(const ProgressState& s);
  void Finish();  // ends the bar's line

 private:
  using Clock = std::chrono::steady_clock;
  bool tty_;
  Clock::time_point start_, phase_start_, last_print_;
  std::string phase_;
  bool drawn_ = false;
};

}  // namespace wavebake::cli
