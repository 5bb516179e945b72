#pragma once
// How a followed job looks on stderr (DESIGN.md §5 "Long work shows a
// progress bar on a terminal and plain progress lines otherwise"): each
// event of driver/job_watch.h drives the bar of cli/progress.h with the
// coordinator's own rays/s, ETA and per-phase task counts, and the notable
// events (failures, expired leases, restarts) get a line of their own.
#include <functional>

#include "cli/progress.h"
#include "wavebake.pb.h"

namespace wavebake::cli {

class WatchDisplay {
 public:
  explicit WatchDisplay(bool quiet) : quiet_(quiet) {}
  ~WatchDisplay() { Finish(); }

  void Show(const v1::JobEvent& event);
  // For driver::WatchOptions::on_event; the display must outlive the watch.
  std::function<void(const v1::JobEvent&)> Callback() {
    return [this](const v1::JobEvent& e) { Show(e); };
  }
  void Finish();  // ends the bar's line (also on destruction)

 private:
  bool quiet_;
  ProgressReporter reporter_;
};

}  // namespace wavebake::cli
