#pragma once
// Names and validation of BakeParams: the one place that knows the spelling
// of every flag value (DESIGN.md §5), shared by the CLI, the RPC layer and
// the store's .zattrs.
#include <string>
#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"

namespace wavebake {

std::string_view ToString(ColumnMode m);
std::string_view ToString(WaveletFilter f);
std::string_view ToString(ErrorScope s);
std::string_view ToString(LevelScaling s);
std::string_view ToString(Transport t);
absl::StatusOr<ColumnMode> ParseColumnMode(std::string_view s);        // adaptive|full|2d
absl::StatusOr<WaveletFilter> ParseWaveletFilter(std::string_view s);  // haar|daub4|legall53|cdf97
absl::StatusOr<ErrorScope> ParseErrorScope(std::string_view s);        // matrix|column
absl::StatusOr<LevelScaling> ParseLevelScaling(std::string_view s);    // uniform|paper
absl::StatusOr<Transport> ParseTransport(std::string_view s);          // diffuse|visibility

// 0..kMaxBounces or "auto" (kAutoBounces), and back.
absl::StatusOr<int> ParseBounces(std::string_view s);
std::string BouncesToString(int bounces);

// Checks every field; the message names the bad field (e.g. "light_res: 33 is
// not a power of two in 8..256"). The layout string is checked by ParseLayout.
absl::Status ValidateBakeParams(const BakeParams& p);

}  // namespace wavebake
