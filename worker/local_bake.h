#pragma once
// The single-process driver (DESIGN.md §2, §5 `wavebake bake` without a
// cluster): plan → BAKE_TILE × tiles → TRANSFORM_COLUMNS × groups → FINALIZE,
// the tasks on a pool of threads, in a temp directory beside the output that
// becomes the output only when everything succeeded. The tasks are the same
// functions a remote worker runs; this file only schedules them.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/bake_params.h"

namespace wavebake {

struct BakeProgress {
  std::string phase;            // "bake tiles", "transform columns", "finalize"
  int64_t done = 0, total = 0;  // tasks of the phase
  uint64_t rays = 0;            // rays traced so far in the job
};

struct LocalBakeOptions {
  int threads = 0;  // 0 = one per hardware thread
  bool keep_staging = false;
  // Called at the start of each phase and after each task, never
  // concurrently (calls are serialized), from whichever thread finished.
  std::function<void(const BakeProgress&)> progress;
};

struct BakeSummary {
  int tiles = 0, groups = 0;
  uint64_t samples = 0;
  uint64_t rays_traced = 0;
  uint64_t staging_bytes = 0;  // compressed bytes BAKE_TILE wrote
  int bits = 0;                // quantization bits used (chosen if --bits auto)
  int64_t nnz = 0;
  uint64_t transport_bytes = 0;                        // transport/* on disk
  uint64_t raw_bytes = 0;                              // S·M·4: T as dense float32
  double column_error_mean = 0, column_error_max = 0;  // stats.column_error of the manifest
  double seconds_bake = 0, seconds_columns = 0, seconds_finalize = 0;
};

// Bakes `scene_spec` with `params` into the store `out`. The store is built
// in `out` + ".partial-<pid>" and renamed to `out` at the end; on any error
// the partial directory is removed, so nothing half-written is left. An
// existing store at `out` is replaced atomically (rename exchange); any other
// existing path is refused (AlreadyExists naming "out"). Invalid params fail
// before anything is created, with the message naming the field.
absl::StatusOr<BakeSummary> RunLocalBake(std::string_view scene_spec, const BakeParams& params,
                                         const std::filesystem::path& out,
                                         const LocalBakeOptions& options);

}  // namespace wavebake
