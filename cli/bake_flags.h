#pragma once
// The bake flags of DESIGN.md §5, shared by `bake` and `submit`.
#include <CLI/CLI.hpp>
#include <string>

#include "absl/status/statusor.h"
#include "core/bake_params.h"

namespace wavebake::cli {

// Raw flag values as typed; ToParams turns them into validated BakeParams.
struct BakeFlags {
  int light_res = 32;
  std::string layout = "camera";
  int supersample = 4;
  std::string row_filter = "haar";
  std::string column_mode = "adaptive";
  std::string column_filter = "haar";
  double target_error = 0.01;
  std::string error_scope = "matrix";
  int column_terms = 0;
  std::string bits = "auto";
  std::string level_scaling = "uniform";
  uint64_t seed = 1;
  bool keep_staging = false;
  std::string refine = "on";
  int tile_size = 32;      // BAKE_TILE edge (DESIGN.md §2)
  int column_group = 256;  // columns per TRANSFORM_COLUMNS task
};

void AddBakeFlags(CLI::App& cmd, BakeFlags& f);
absl::StatusOr<BakeParams> ToParams(const BakeFlags& f);

}  // namespace wavebake::cli
