#pragma once
// Every numeric result is finite or an error. Inputs are bounded where they
// enter (kMaxEnvRadiance for environments and area-light radiance, the
// store's arrays finite), yet a product of bounded inputs can still leave
// float: this is the last check before a relit image is returned, written or
// compared, so that an overflow says which input caused it instead of
// passing NaN (masked) or inf (white, or black after tone mapping) for a
// picture with rc 0.
#include <cstdint>
#include <span>
#include <string_view>

#include "absl/status/status.h"

namespace wavebake {

// rgb [cells * 3] of a W×H sample grid; grid[cell] < 0 marks a masked cell,
// NaN by convention. Any other value that is NaN or ±inf is
// InvalidArgument naming the cell (x, y), the channel and `inputs` (what
// the caller lit the store with: "the environment", "area light 'L.json'").
absl::Status CheckRelitFinite(std::span<const float> rgb, std::span<const int32_t> grid, int width,
                              std::string_view inputs);

// An exposure multiplies a relit image by 2^stops in float: beyond ±126
// stops that factor is inf or 0 (and inf × 0 is NaN), a NaN exposure turned
// every tone-mapped pixel black. InvalidArgument naming `exposure`.
inline constexpr double kMaxExposureStops = 126;
absl::Status CheckExposure(double stops);

}  // namespace wavebake
