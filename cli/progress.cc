#include "cli/progress.h"

#include <unistd.h>

#include <cstdio>

namespace wavebake::cli {

ProgressReporter::ProgressReporter()
    : tty_(isatty(STDERR_FILENO) != 0),
      start_(Clock::now()),
      phase_start_(start_),
      last_print_(start_) {}

void ProgressReporter::Update(const ProgressState& s) {
  const auto now = Clock::now();
  const bool new_phase = s.phase != phase_;
  if (new_phase) {
    if (drawn_ && tty_) std::fputc('\n', stderr);
    phase_ = s.phase;
    phase_start_ = now;
  }
  const bool last = s.total > 0 && s.done == s.total;
  if (!tty_ && !new_phase && !last && now - last_print_ < std::chrono::seconds(3)) return;
  if (tty_ && !new_phase && !last && now - last_print_ < std::chrono::milliseconds(100)) return;
  last_print_ = now;

  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double in_phase = std::chrono::duration<double>(now - phase_start_).count();
  const double frac = s.total > 0 ? double(s.done) / double(s.total) : 0;
  const double eta = frac > 0 ? in_phase * (1 - frac) / frac : 0;
  const double mrays = elapsed > 0 ? s.rays / elapsed / 1e6 : 0;
  char bar[31];
  const int filled = static_cast<int>(frac * 30);
  for (int i = 0; i < 30; ++i) bar[i] = i < filled ? '#' : '.';
  bar[30] = 0;
  std::fprintf(stderr, "%s%-18s [%s] %3d%% %lld/%lld  %.1f Mrays/s  ETA %.0fs%s", tty_ ? "\r" : "",
               s.phase.c_str(), bar, static_cast<int>(frac * 100), static_cast<long long>(s.done),
               static_cast<long long>(s.total), mrays, eta, tty_ ? "\033[K" : "\n");
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressReporter::Finish() {
  if (drawn_ && tty_) std::fputc('\n', stderr);
  drawn_ = false;
}

}  // namespace wavebake::cli
