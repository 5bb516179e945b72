#pragma once
// The bake parameters a user spells in words (the command line's flags, a
// front end's keywords), parsed over the numeric ones by core/bake/bake_params_io.h,
// so that every front end, the RPC and the store refuse the same strings.
#include <string>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"

namespace wavebake {

struct BakeParamWords {
  std::string row_filter = "haar", column_mode = "adaptive", column_filter = "haar",
              error_scope = "matrix", bits = "auto", level_scaling = "uniform",
              transport = "diffuse", light_domain = "cube", refine = "on", bounces = "0";
  bool allow_uv_overlap = false;  // uv layouts: the layout's ",allow-overlap"
};

// `numbers` with the words parsed into it, then validated as a whole. Errors
// name the field (e.g. "column_mode: 'fast' is not adaptive, full or 2d").
absl::StatusOr<BakeParams> ParseBakeParamWords(BakeParams numbers, const BakeParamWords& words);

}  // namespace wavebake
