#include "cli/progress.h"

#include <unistd.h>

#include <cstdio>

#include "cli/command_error.h"
#include "driver/jobs/job_query.h"
#include "driver/jobs/job_text.h"
#include "driver/jobs/job_watch.h"

namespace wavebake::cli {

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
  const auto every = tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(3000);
  if (!new_phase && !last && now - last_print_ < every) return;
  last_print_ = now;

  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "%s%s%s", tty_ ? "\r" : "", driver::ProgressText(e, elapsed).c_str(),
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
