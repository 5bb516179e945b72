#include "cli/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "cli/command_error.h"
#include "driver/job_query.h"
#include "driver/job_watch.h"

namespace wavebake::cli {
namespace {

std::string PhaseLabel(v1::Phase p) {
  switch (p) {
    case v1::PHASE_BAKING:
      return "bake tiles";
    case v1::PHASE_TRANSFORMING:
      return "transform columns";
    case v1::PHASE_FINALIZING:
      return "finalize";
    default:  // PHASE_DONE -> "done"
      return absl::AsciiStrToLower(v1::Phase_Name(p).substr(6));
  }
}

}  // namespace

ProgressBar::ProgressBar(bool quiet)
    : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0), start_(Clock::now()), last_print_(start_) {}

void ProgressBar::Show(const v1::JobEvent& e) {
  if (quiet_) return;
  if (const std::string notable = driver::NotableEventText(e); !notable.empty())
    std::fprintf(stderr, "\n%s\n", notable.c_str());
  if (e.phase() == v1::PHASE_QUEUED) return;
  const auto now = Clock::now();
  const bool new_phase = e.phase() != phase_;
  if (new_phase) {
    if (drawn_ && tty_) std::fputc('\n', stderr);
    phase_ = e.phase();
  }
  const int64_t done = e.phase_tasks_done(), total = e.phase_tasks_total();
  const bool last = total > 0 && done == total;
  if (!tty_ && !new_phase && !last && now - last_print_ < std::chrono::seconds(3)) return;
  if (tty_ && !new_phase && !last && now - last_print_ < std::chrono::milliseconds(100)) return;
  last_print_ = now;

  // The coordinator's rate when it sent one (>= 0), else our own clock's; its
  // ETA is the whole job's from measured task times (coordinator/eta_model.h).
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double frac = total > 0 ? double(done) / double(total) : 0;
  const double mrays = e.rays_per_second() >= 0 ? e.rays_per_second() / 1e6
                       : elapsed > 0            ? e.rays_traced() / elapsed / 1e6
                                                : 0;
  const std::string eta =
      e.eta_seconds() >= 0 ? absl::StrCat(std::lround(e.eta_seconds()), "s") : "--";
  char bar[31];
  const int filled = static_cast<int>(frac * 30);
  for (int i = 0; i < 30; ++i) bar[i] = i < filled ? '#' : '.';
  bar[30] = 0;
  std::fprintf(stderr, "%s%-18s [%s] %3d%% %lld/%lld  %.1f Mrays/s  ETA %s%s", tty_ ? "\r" : "",
               PhaseLabel(e.phase()).c_str(), bar, static_cast<int>(frac * 100),
               static_cast<long long>(done), static_cast<long long>(total), mrays, eta.c_str(),
               tty_ ? "\033[K" : "\n");
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::Finish() {
  if (drawn_ && tty_) std::fputc('\n', stderr);
  drawn_ = false;
}

v1::Job FollowJob(const driver::Client& client, const std::string& job_id, const char* command,
                  double patience_seconds) {
  ProgressBar display(/*quiet=*/false);
  absl::StatusOr<v1::Job> job = driver::WatchJob(
      client, job_id, {.patience_seconds = patience_seconds, .on_event = display.Callback()});
  display.Finish();
  if (!job.ok()) Fail(command, job.status());
  if (job->phase() != v1::PHASE_DONE) Fail(command, driver::JobOutcome(*job));
  return *job;
}

}  // namespace wavebake::cli
