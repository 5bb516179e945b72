#pragma once
// Checks a BakeRequest field by field and fills in the defaults of DESIGN.md
// §5, so a stored job always shows its effective parameters. Every error is
// INVALID_ARGUMENT and its message starts with the field path (§4), e.g.
// "light_res: 33 is not a power of two in 8..256".
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/bake_params.h"
#include "wavebake.pb.h"

namespace wavebake {

inline constexpr int kDefaultMaxAttempts = 3;

absl::Status NormalizeBakeRequest(v1::BakeRequest& request);

// The core parameters of a normalized request (for the planner and workers).
absl::StatusOr<BakeParams> ToBakeParams(const v1::BakeRequest& request);

// "builtin:NAME" or "NAME" -> "NAME"; empty if the request has no built-in.
std::string BuiltinSceneName(const v1::BakeRequest& request);

}  // namespace wavebake
