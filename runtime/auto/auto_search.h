#pragma once
// The search policy of `wavebake bake --auto --target-error E`:
// the light resolution N, the column target and (through --bits auto) the
// bits of the smallest store whose relighting stays within E of the
// independent reference (runtime/reference/reference.h). Pure decisions from
// measurements, no I/O: the orchestration (driver/bake/auto_bake.h) asks Next() what
// to measure, measures it and reports back.
//
// The error model: against the reference, the relit store's relative RMS
// error splits as  e_tot² ≈ e_disc(N)² + e_comp²  (+ the reference's own
// SE², which the caller keeps below E/5 and does not subtract: the measured
// e_tot is then slightly pessimistic, never optimistic). e_disc(N) is the
// error of the dense cubemap T at N (runtime/reference/dense_trace.h) and falls with
// N; e_comp is what the column selection and quantization add, set by the
// column target. So, for N = 8, 16, 32, ... in turn:
//   1. measure e_disc(N) (a dense trace: no column stage, no store);
//   2. if e_disc(N) > disc_share·E, too little is left for compression: next N;
//   3. else bake with column target = safety·sqrt(E² − e_disc²) (the matrix
//      scope target bounds the relative error of every relighting; the
//      relighting error is usually well below it) and measure e_tot with all
//      wavelet lights;
//   4. e_tot ≤ E: this N is the answer — store bytes grow ~2.5× per
//      doubling of N, so the first N that meets E holds the smallest store.
//      If the measured e_comp = sqrt(e_tot² − e_disc²) used well under its
//      budget (the relighting error is often a third of the column target),
//      bake once more with the target loosened in proportion and keep the
//      smaller store that meets E.
//      e_tot > E: retry once at this N with the target scaled by the
//      measured overshoot of e_comp, then go on to the next N.
// Nothing meets E up to the last N: failed, with the closest candidate named.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wavebake {

struct AutoSearchConfig {
  double target_error = 0.05;                           // E
  std::vector<int> resolutions = {8, 16, 32, 64, 128};  // tried in order
  double disc_share = 0.95;                             // skip N when e_disc > disc_share·E
  double safety = 0.8;               // column target = safety·sqrt(E² − e_disc²)
  double min_column_target = 0.001;  // below this the store balloons for nothing
  int bakes_per_resolution = 2;      // the first bake and one tightened retry
  double min_loosen = 1.5;           // loosen only when the target can grow this much
  double max_loosen = 4;             // and at most this much
};

// What a bake at (N, column target) produced, as measured by the caller.
struct AutoBakeMeasurement {
  int bits = 0;
  int64_t bytes = 0;         // the store on disk
  double e_tot = 0;          // all wavelet lights vs the reference
  double e_tot_default = 0;  // the runtime's default number of lights vs the reference
  double seconds = 0;        // bake + measurement
};

// One row of the search: a resolution whose e_disc was measured, and (when
// baked) what the bake gave.
struct AutoCandidate {
  int light_res = 0;
  double e_disc = 0;
  bool baked = false;
  double column_target = 0;  // baked only
  AutoBakeMeasurement bake;  // baked only
  bool meets = false;        // baked and e_tot ≤ E
};

enum class AutoStep { kMeasureDisc, kBake, kDone, kFailed };

struct AutoAction {
  AutoStep step = AutoStep::kFailed;
  int light_res = 0;         // kMeasureDisc, kBake
  double column_target = 0;  // kBake
  std::string reason{};      // kFailed
};

// sqrt(E² − e_disc²)·safety clamped below by min_column_target, or nullopt
// when e_disc > disc_share·E (N too coarse for E).
std::optional<double> ColumnTargetFor(const AutoSearchConfig& config, double e_disc);

// The retry's target after a bake at `column_target` measured e_tot > E: the
// measured compression error sqrt(e_tot² − e_disc²) is scaled down to the
// budget sqrt(E² − e_disc²)·safety by shrinking the target in proportion
// (e_comp ∝ target to first order), and at least to 0.7× the old target.
// nullopt when that would go below min_column_target.
std::optional<double> TightenedColumnTarget(const AutoSearchConfig& config, double e_disc,
                                            double column_target, double e_tot);

// The second bake's target after a first bake at `column_target` met E
// with e_comp under budget: the target grown by budget / e_comp, at most
// max_loosen× (and to 1, the largest valid target); nullopt when it would
// grow less than min_loosen×.
std::optional<double> LoosenedColumnTarget(const AutoSearchConfig& config, double e_disc,
                                           double column_target, double e_tot);

class AutoSearch {
 public:
  explicit AutoSearch(AutoSearchConfig config);

  AutoAction Next() const;
  // The answers to kMeasureDisc and kBake, for the action Next() returned.
  void OnDisc(double e_disc);
  void OnBaked(const AutoBakeMeasurement& measurement);

  const AutoSearchConfig& config() const { return config_; }
  const std::vector<AutoCandidate>& candidates() const { return candidates_; }
  // Index into candidates() of the chosen bake, once Next() is kDone.
  std::optional<size_t> chosen() const { return chosen_; }

 private:
  void Advance();
  std::string FailureReason() const;

  AutoSearchConfig config_;
  std::vector<AutoCandidate> candidates_;
  size_t res_index_ = 0;
  std::optional<double> e_disc_;  // of resolutions[res_index_], once measured
  std::optional<double> next_target_;
  int bakes_ = 0;               // at resolutions[res_index_]
  bool loosening_ = false;      // the pending bake is the loosened one
  std::optional<size_t> best_;  // the smallest store so far that met E
  std::optional<size_t> chosen_;
};

}  // namespace wavebake
