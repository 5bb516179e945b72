#include "cli/watch_display.h"

#include <cstdio>

#include "absl/strings/ascii.h"
#include "driver/job_watch.h"

namespace wavebake::cli {
namespace {

const char* PhaseLabel(v1::Phase p) {
  switch (p) {
    case v1::PHASE_BAKING:
      return "bake tiles";
    case v1::PHASE_TRANSFORMING:
      return "transform columns";
    case v1::PHASE_FINALIZING:
      return "finalize";
    default:
      return nullptr;
  }
}

}  // namespace

void WatchDisplay::Show(const v1::JobEvent& e) {
  if (quiet_) return;
  if (const std::string notable = driver::NotableEventText(e); !notable.empty())
    std::fprintf(stderr, "\n%s\n", notable.c_str());
  if (e.phase() == v1::PHASE_QUEUED) return;
  ProgressState s;
  const char* label = PhaseLabel(e.phase());
  s.phase = label ? label : absl::AsciiStrToLower(v1::Phase_Name(e.phase()).substr(6));
  s.done = e.phase_tasks_done();
  s.total = e.phase_tasks_total();
  s.rays = static_cast<uint64_t>(e.rays_traced());
  s.rays_per_second = e.rays_per_second();
  s.eta_seconds = e.eta_seconds();
  reporter_.Update(s);
}

void WatchDisplay::Finish() {
  if (!quiet_) reporter_.Finish();
}

}  // namespace wavebake::cli
