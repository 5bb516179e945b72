#pragma once
// A followed job on stderr (DESIGN.md §5 "Long work shows a progress bar on
// a terminal and plain progress lines otherwise"): each event of
// driver/jobs/job_watch.h redraws the bar with the coordinator's own per-phase
// task counts, rays/s and ETA; the notable events (failures, expired leases,
// restarts) get a line of their own.
#include <chrono>
#include <functional>
#include <string>

#include "driver/jobs/client.h"

namespace wavebake::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet);
  ~ProgressBar() { Finish(); }

  void Show(const v1::JobEvent& event);
  // For driver::WatchOptions::on_event; the bar must outlive the watch.
  std::function<void(const v1::JobEvent&)> Callback() {
    return [this](const v1::JobEvent& e) { Show(e); };
  }
  void Finish();  // ends the bar's line (also on destruction)

 private:
  using Clock = std::chrono::steady_clock;
  bool quiet_, tty_;
  Clock::time_point start_, last_print_;
  v1::Phase phase_ = v1::PHASE_UNSPECIFIED;
  bool drawn_ = false;
};

// Follows the job to its end under a progress bar (`watch`, `submit --wait`):
// returns it if it ended DONE, else fails `command` with its outcome.
v1::Job FollowJob(const driver::Client& client, const std::string& job_id, const char* command,
                  double patience_seconds = 60);

}  // namespace wavebake::cli
