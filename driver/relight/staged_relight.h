#pragma once
// The dense, uncompressed T of a bake relit straight from its staging
// (worker/tiles/recode.h TraceStaging): B = T·L with T the traced rows as the bake
// traced them (refined or brute force) and L the lighting on the same
// cubemap, both in the row-transform basis (orthonormal, so it is T·L of the
// pixel basis). It is the bake's own discretization error without a second
// trace: what `bake --auto` judges a light resolution by before any column
// stage (driver/bake/auto_bake.h).
#include <filesystem>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "worker/tiles/bake_context.h"

namespace wavebake::driver {

// ctx: the trace's context (its plan, samples and row filter). cube_rgb:
// [3 · 6N²] texel mean radiance (runtime/env/env_resample.h ResampleToCubemap).
// Returns [cells·3] × albedo, NaN where masked, like runtime/reference/dense_trace.h.
absl::StatusOr<std::vector<float>> RelightStaging(const BakeContext& ctx,
                                                  const std::filesystem::path& traced,
                                                  std::span<const float> cube_rgb);

}  // namespace wavebake::driver
