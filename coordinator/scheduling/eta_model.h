#pragma once
// How long a job still runs (Job.eta_seconds, JobEvent.eta_seconds;
// DESIGN.md §4 Watch), from what its tasks took so far.
//
// A job runs three stages in order (§2): tiles, column groups, FINALIZE.
// The current stage's remaining wall time is the work left in it — pending
// tasks at the stage's mean measured task time t, running ones at t minus
// their age — spread over the job's parallelism P, but never less than the
// longest single remaining task. Until a task of the stage is done, t comes
// from a prior (below), raised to the age of the oldest running task (it
// takes at least that long); the tile stage, whose work is ray tracing, uses
// its ray fraction instead while no tile is done. Stages not begun yet are
// priors scaled by the tile stage's wall time B: both the tile stage and the
// column stage touch every entry of the S×M matrix once, so their ratio is
// roughly a property of the machine and the parameters, not of the scene.
#include <array>
#include <vector>

namespace wavebake {

// Priors: column stage wall ≈ kColumnStageRatio · B, FINALIZE ≈
// kFinalizeRatio · B. Measured with the default parameters (N = 32, K = 4,
// adaptive columns, 2 workers): cubes-wall 0.17 and 0.23, the bunny
// (hilbert:64x64) 0.25 and 0.41. They only matter until the stage's first
// task is done.
inline constexpr double kColumnStageRatio = 0.25;
inline constexpr double kFinalizeRatio = 0.3;

struct StageProgress {
  int tasks = 0;                // in the stage
  int done = 0;                 // done so far (measured or not)
  int measured = 0;             // done tasks whose lease-to-complete time is known
  double measured_seconds = 0;  // their sum
  std::vector<double> running;  // ages (s) of the stage's leased tasks
};

struct EtaInputs {
  std::array<StageProgress, 3> stages;  // tiles, groups, finalize
  int current = 0;                      // the stage running now (0..2)
  double stage_elapsed = 0;             // seconds since the current stage opened
  double tile_stage_seconds = -1;       // B once the tile stage is over, else −1
  double tile_rays_fraction = -1;       // rays traced / estimated, while baking; −1 unknown
  int parallelism = 1;                  // tasks the job ran at once (its peak)
};

// Seconds until the job is done; −1 when nothing is known yet (no task
// leased and no ray traced).
double EstimateEta(const EtaInputs& in);

}  // namespace wavebake
