#pragma once
// The bounces' record in a finished store's .zattrs (FINALIZE,
// worker/columns/finalize.h): only a store baked with bounces has one, so 0-bounce
// stores keep their bytes.
#include <filesystem>

#include "absl/status/status.h"
#include "nlohmann/json.hpp"
#include "worker/tiles/bake_context.h"

namespace wavebake {

// manifest["bounces"] = {count, gather_rays, gather_entries, energy[b] (Σ T_b²
// over the matrix, summed from staging/bounce_energy in group order),
// rms_ratio[b] = √(energy[b]/energy[0]), convention} when ctx.plan.bounces > 0,
// {count: 0} for an `auto` that chose none; and, for `auto`, its estimates
// and rule under "auto". Nothing for params.bounces 0.
absl::Status AddBounceRecord(const BakeContext& ctx, const std::filesystem::path& store,
                             nlohmann::json& manifest);

}  // namespace wavebake
