#pragma once
// Relighting errors against the independent reference (runtime/reference/reference.h)
// for one scene, layout and environment, with the reference traced once:
// the dense cubemap T at any N (runtime/reference/dense_trace.h, the discretization
// error e_disc(N)) and any baked store of that scene (the total e_tot).
// Shared by `bake --auto` (driver/bake/auto_bake.h) and the light-resolution chart
// (bench/charts_data.cc). The metric is eval's rel_rms (runtime/reference/eval.h).
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/reference.h"

namespace wavebake {
struct BakeContext;
}

namespace wavebake::driver {

class ReferenceMeasure {
 public:
  // Lays out the scene's samples as `params` does (its light_res is not
  // used), loads env_spec and traces the reference to target_rel_se with
  // the bake's ray offset. Errors name the scene, layout or env.
  static absl::StatusOr<std::unique_ptr<ReferenceMeasure>> Create(const std::string& scene,
                                                                  const BakeParams& params,
                                                                  const std::string& env_spec,
                                                                  double target_rel_se);
  ~ReferenceMeasure();

  const ReferenceResult& reference() const { return reference_; }
  int samples() const;

  // e_disc(N): the dense T at light_res (the params' supersample and seed),
  // relit under env, against the reference.
  absl::StatusOr<double> DenseError(int light_res) const;
  // e_disc of a bake's own trace (worker/tiles/recode.h TraceStaging): its dense
  // staged T relit under env (driver/relight/staged_relight.h) against the
  // reference. trace_ctx is the trace's context (same scene and layout).
  absl::StatusOr<double> StagingError(const BakeContext& trace_ctx,
                                      const std::filesystem::path& traced) const;
  // e_tot of a store of this scene relit by each of `terms` wavelet lights
  // (≥ 6N² is all of them); also its bits.
  absl::StatusOr<std::vector<double>> StoreErrors(const std::filesystem::path& store,
                                                  std::span<const int> terms,
                                                  int* bits = nullptr) const;

 private:
  ReferenceMeasure(std::unique_ptr<BakeContext> ctx, EnvMap env, ReferenceResult reference);
  std::unique_ptr<BakeContext> ctx_;
  EnvMap env_;
  ReferenceResult reference_;
};

}  // namespace wavebake::driver
