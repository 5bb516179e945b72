#pragma once
// `wavebake bake SCENE --auto --target-error E [--env ENV]`: the
// orchestration of the search in runtime/auto_search.h. It traces the
// independent reference (runtime/reference.h) once for the scene's samples
// and ENV, measures the dense cubemap error e_disc(N) per light resolution
// (runtime/dense_trace.h), bakes candidates with the embedded bake
// (driver/embedded_bake.h) into a temporary directory beside the output,
// relights each under ENV (all wavelet lights, and the runtime's default
// number) against the reference, and publishes only the chosen store at
// the output with an "auto" object in its .zattrs recording what was tried
// and measured. Nothing else is left behind, whatever the outcome.
#include <atomic>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "absl/status/statusor.h"
#include "core/bake_params.h"
#include "runtime/auto_search.h"
#include "wavebake.pb.h"

namespace wavebake::driver {

// The lighting `--auto` judges by when --env is absent: builtin:sky has a
// small, very bright sun, the conservative case (it needs the finest
// cubemap of the built-ins).
inline constexpr char kDefaultAutoEnv[] = "builtin:sky";
// The runtime's default number of wavelet lights (`relight`, `eval`).
inline constexpr int kDefaultRelightTerms = 256;

struct AutoBakeOptions {
  std::string env = kDefaultAutoEnv;
  AutoSearchConfig search;  // its target_error is E
  int workers = 0;
  // What the search is doing, a line at a time ("N=32: baking with column
  // target 0.0302"), and each candidate bake's job events.
  std::function<void(const std::string&)> on_message = {};
  std::function<void(const v1::JobEvent&)> on_event = {};
  const std::atomic<bool>* interrupted = nullptr;
};

struct AutoBakeReport {
  AutoSearch search{AutoSearchConfig{}};
  std::string failure;          // non-empty: no candidate met E, nothing written
  double reference_rel_se = 0;  // the reference's own error (kept, not subtracted)
  double reference_seconds = 0;
  double seconds = 0;     // the whole search
  nlohmann::json record;  // the "auto" object written to .zattrs
};

// Errors: bad input (scene, env, output path, params; named by field), a
// failed or interrupted candidate bake (then nothing is at `out`). A search
// that ends without meeting E is not an error: report.failure says why.
absl::StatusOr<AutoBakeReport> AutoBake(const std::string& scene, const BakeParams& base,
                                        const std::filesystem::path& out,
                                        const AutoBakeOptions& options);

// The candidates as a table (N, e_disc, column target, bits, bytes, e_tot
// with all lights and at kDefaultRelightTerms, seconds) and the choice.
std::string AutoBakeTable(const AutoBakeReport& report);

}  // namespace wavebake::driver
