#include "runtime/relight/finite_output.h"

#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"

namespace wavebake {

absl::Status CheckRelitFinite(std::span<const float> rgb, std::span<const int32_t> grid, int width,
                              std::string_view inputs) {
  if (rgb.size() != 3 * grid.size() || width <= 0)
    return absl::InternalError(
        absl::StrCat("relit image of ", rgb.size(), " values for ", grid.size(), " cells"));
  for (size_t cell = 0; cell < grid.size(); ++cell) {
    if (grid[cell] < 0) continue;
    for (int c = 0; c < 3; ++c) {
      const float v = rgb[3 * cell + c];
      if (std::isfinite(v)) continue;
      return absl::InvalidArgumentError(absl::StrCat(
          "relit value of cell (", cell % width, ", ", cell / width, ") channel ",
          std::string(1, "RGB"[c]), " is ", std::isnan(v) ? "NaN" : (v > 0 ? "+inf" : "-inf"), ": ",
          std::string(inputs),
          " overflowed single precision in the product with the store's transport; scale it "
          "down"));
    }
  }
  return absl::OkStatus();
}

absl::Status CheckExposure(double stops) {
  if (std::isfinite(stops) && std::abs(stops) <= kMaxExposureStops) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat("exposure: ", stops,
                                                 " stops; need a finite number of stops within ±",
                                                 kMaxExposureStops, " (2^stops as a float)"));
}

}  // namespace wavebake
