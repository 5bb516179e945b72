#pragma once
// The bake flags of DESIGN.md §5, shared by `bake` and `submit`. Numbers bind
// straight to BakeParams; names are parsed by core/bake_params_io.h, so the
// command line, the RPC and the store refuse the same strings.
#include <CLI/CLI.hpp>
#include <string>

#include "absl/status/statusor.h"
#include "core/bake_params.h"

namespace wavebake::cli {

struct BakeFlags {
  BakeParams params;  // the numeric flags, and the defaults of the named ones
  std::string row_filter = "haar", column_mode = "adaptive", column_filter = "haar",
              error_scope = "matrix", bits = "auto", level_scaling = "uniform",
              transport = "diffuse", light_domain = "cube", refine = "on";
  bool allow_uv_overlap = false;  // uv layouts: the layout's ",allow-overlap"
};

void AddBakeFlags(CLI::App& cmd, BakeFlags& f);
// Errors name the field (e.g. "column_mode: 'fast' is not adaptive, full or 2d").
absl::StatusOr<BakeParams> ToParams(const BakeFlags& f);

}  // namespace wavebake::cli
