#include "coordinator/scheduling/eta_model.h"

#include <algorithm>

namespace wavebake {
namespace {

double MeanTaskSeconds(const StageProgress& s) {
  return s.measured > 0 ? s.measured_seconds / s.measured : -1;
}

double OldestRunning(const StageProgress& s) {
  double oldest = 0;
  for (double age : s.running) oldest = std::max(oldest, age);
  return oldest;
}

// Wall time left in a stage whose tasks take t seconds each.
double StageRemaining(const StageProgress& s, double t, int parallelism) {
  const int pending = std::max(0, s.tasks - s.done - static_cast<int>(s.running.size()));
  double work = pending * t, longest = pending > 0 ? t : 0;
  for (double age : s.running) {
    const double left = std::max(0.0, t - age);
    work += left;
    longest = std::max(longest, left);
  }
  return std::max(work / parallelism, longest);
}

// A stage's task time: measured, else its prior raised to the oldest
// running task's age.
double TaskSeconds(const StageProgress& s, double prior) {
  const double mean = MeanTaskSeconds(s);
  return mean >= 0 ? mean : std::max(prior, OldestRunning(s));
}

}  // namespace

double EstimateEta(const EtaInputs& in) {
  const int current = std::clamp(in.current, 0, 2);
  const int p = std::max(1, in.parallelism);
  const StageProgress& tiles = in.stages[0];
  double remaining = 0;
  double tile_wall = std::max(0.0, in.tile_stage_seconds);
  if (current == 0) {
    const double f = std::min(1.0, in.tile_rays_fraction);
    if (MeanTaskSeconds(tiles) >= 0) {
      remaining = StageRemaining(tiles, MeanTaskSeconds(tiles), p);
    } else if (f > 0) {
      remaining = in.stage_elapsed * (1 - f) / f;
    } else if (!tiles.running.empty()) {
      remaining = StageRemaining(tiles, OldestRunning(tiles), p);  // a lower bound
    } else {
      return -1;
    }
    tile_wall = in.stage_elapsed + remaining;
  }
  const StageProgress& groups = in.stages[1];
  const double column_wall = kColumnStageRatio * tile_wall;
  if (current == 0) remaining += column_wall;
  if (current == 1) {
    const double prior = column_wall * p / std::max(1, groups.tasks);
    remaining += StageRemaining(groups, TaskSeconds(groups, prior), p);
  }
  const StageProgress& finalize = in.stages[2];
  const double finalize_wall = kFinalizeRatio * tile_wall;
  if (current < 2) remaining += finalize_wall;
  if (current == 2) remaining += StageRemaining(finalize, TaskSeconds(finalize, finalize_wall), 1);
  return remaining;
}

}  // namespace wavebake
