#pragma once
// `wavebake bake SCENE --auto --target-error E [--env ENV]...`: the
// orchestration of the search in runtime/auto/auto_search.h, judged by every ENV
// given (the worst error counts: a store chosen for one lighting can miss E
// under another of the same kind). It traces the independent reference
// (runtime/reference/reference.h) once per ENV for the scene's samples; traces each
// light resolution N once (worker/tiles/recode.h TraceStaging), into a temporary
// directory beside the output, and measures e_disc(N) by relighting that
// dense traced T itself (driver/relight/staged_relight.h); codes every candidate
// column target from the same trace (worker/tiles/recode.h Recode), relights it
// under every ENV (all wavelet lights, and the runtime's default number)
// against the references; and publishes only the chosen store at the output
// with an "auto" object in its .zattrs recording what was tried and
// measured. Nothing else is left behind, whatever the outcome.
#include <atomic>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "runtime/auto/auto_search.h"

namespace wavebake::driver {

// The lighting `--auto` judges by when --env is absent: builtin:sky has a
// small, very bright sun, the conservative case (it needs the finest
// cubemap of the built-ins).
inline constexpr char kDefaultAutoEnv[] = "builtin:sky";
// The runtime's default number of wavelet lights (`relight`, `eval`).
inline constexpr int kDefaultRelightTerms = 256;

struct AutoBakeOptions {
  std::vector<std::string> envs = {kDefaultAutoEnv};  // at least one
  AutoSearchConfig search;                            // its target_error is E
  int workers = 0;  // threads of the traces and column stages; 0 = one per hardware thread
  // What the search is doing, a line at a time ("N=32: coding with column
  // target 0.0302", a trace's progress).
  std::function<void(const std::string&)> on_message = {};
  const std::atomic<bool>* interrupted = nullptr;
};

struct AutoBakeReport {
  AutoSearch search{AutoSearchConfig{}};
  std::string failure;           // non-empty: no candidate met E, nothing written
  double reference_rel_se = 0;   // the largest of the references' own errors (kept, not subtracted)
  double reference_seconds = 0;  // all references
  // Per candidate row of search.candidates(): each env's e_disc, and (baked)
  // e_tot with all lights and with kDefaultRelightTerms, in options.envs order.
  std::vector<std::vector<double>> e_disc_by_env, e_tot_by_env, e_tot_default_by_env;
  std::vector<std::string> envs;  // as judged by, options.envs
  int traces = 0;                 // light resolutions traced (once each)
  uint64_t rays = 0;              // in all traces
  double seconds = 0;             // the whole search
  nlohmann::json record;          // the "auto" object written to .zattrs
};

// Errors: bad input (scene, env, output path, params; named by field), a
// failed or interrupted candidate bake (then nothing is at `out`). A search
// that ends without meeting E is not an error: report.failure says why.
absl::StatusOr<AutoBakeReport> AutoBake(const std::string& scene, const BakeParams& base,
                                        const std::filesystem::path& out,
                                        const AutoBakeOptions& options);

// The candidates as a table (N, e_disc, column target, bits, bytes, e_tot
// with all lights and at kDefaultRelightTerms — the worst env's —, seconds)
// and the choice; with several envs, the worst env of each row.
std::string AutoBakeTable(const AutoBakeReport& report);

}  // namespace wavebake::driver
