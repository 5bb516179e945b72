// LoadEnvMap (env_map.h): files, layouts, validation, built-ins.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "absl/strings/str_cat.h"
#include "runtime/env/env_builtin.h"
#include "runtime/env/env_cross.h"
#include "runtime/env/env_map.h"
#include "runtime/io/image_io.h"

namespace wavebake {

namespace {

// Radiance must be finite and non-negative: one bad texel would poison every
// relit pixel through T·L. And it must stay below kMaxEnvRadiance (env_map.h),
// or the relighting's single-precision sums overflow and the image is
// silently black (an RGBE exponent of 255 is 1.7e38).
absl::Status CheckRadiance(const std::filesystem::path& path, const EnvMap& image) {
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Vec3 p = image.Pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        if (std::isfinite(p[c]) && p[c] >= 0 && p[c] <= kMaxEnvRadiance) continue;
        const bool huge = std::isfinite(p[c]) && p[c] > 0;
        return absl::InvalidArgumentError(absl::StrCat(
            path.string(), ": pixel (", x, ", ", y, ") channel ", std::string(1, "RGB"[c]), " is ",
            huge ? absl::StrCat(p[c]) : std::to_string(p[c]),
            huge ? absl::StrCat("; radiance above ", kMaxEnvRadiance,
                                " overflows the relighting's float sums (scale the map down)")
                 : "; radiance must be finite and non-negative"));
      }
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<EnvMap> ToLatLong(const std::filesystem::path& path, EnvMap image) {
  const int w = image.width, h = image.height;
  if (w > 0 && w == 2 * h) return image;
  if (w > 0 && w % 3 == 0 && 4 * w == 3 * h) return VerticalCrossToLatLong(image);
  return absl::InvalidArgumentError(
      absl::StrCat(path.string(), ": image is ", w, "x", h,
                   "; expected a 2:1 lat-long map or a 3:4 vertical cross"));
}

std::string Lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

}  // namespace

absl::StatusOr<EnvMap> LoadEnvMap(std::string_view spec) {
  if (spec == "builtin:constant") return MakeConstantEnv();
  if (spec == "builtin:sky") return MakeSkyEnv();
  const std::filesystem::path path(spec);
  if (spec.starts_with("builtin:")) {
    return absl::InvalidArgumentError(
        absl::StrCat("environment '", path.string(), "': unknown built-in (constant|sky)"));
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return absl::NotFoundError(absl::StrCat(path.string(), ": no such environment file"));
  }
  const std::string ext = Lowercase(path.extension().string());
  absl::StatusOr<EnvMap> image;
  if (ext == ".hdr") {
    image = ReadHdrImage(path);
  } else if (ext == ".exr") {
    image = ReadExrImage(path);
  } else {
    return absl::InvalidArgumentError(absl::StrCat(path.string(), ": unknown environment format '",
                                                   ext, "' (expected .hdr or .exr)"));
  }
  if (!image.ok()) return image.status();
  if (absl::Status s = CheckRadiance(path, *image); !s.ok()) return s;
  return ToLatLong(path, *std::move(image));
}

}  // namespace wavebake
