// Image readers of image_io.h backed by stb_image (Debian's libstb).
#include <stb/stb_image.h>

#include <cmath>
#include <memory>

#include "absl/strings/str_cat.h"
#include "runtime/image_io.h"

namespace wavebake {

absl::StatusOr<EnvMap> ReadHdrImage(const std::filesystem::path& path) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<float, void (*)(void*)> data(stbi_loadf(path.c_str(), &w, &h, &channels, 3),
                                               stbi_image_free);
  if (!data) {
    return absl::InvalidArgumentError(
        absl::StrCat(path.string(), ": unreadable Radiance HDR: ", stbi_failure_reason()));
  }
  return EnvMap{w, h, std::vector<float>(data.get(), data.get() + size_t(w) * h * 3)};
}

absl::StatusOr<EnvMap> ReadPngImage(const std::filesystem::path& path) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> data(
      stbi_load(path.c_str(), &w, &h, &channels, 3), stbi_image_free);
  if (!data) {
    return absl::InvalidArgumentError(
        absl::StrCat(path.string(), ": unreadable PNG: ", stbi_failure_reason()));
  }
  // The sRGB EOTF (IEC 61966-2-1), once per code.
  float linear[256];
  for (int i = 0; i < 256; ++i) {
    const double c = i / 255.0;
    linear[i] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
  }
  EnvMap image{w, h, std::vector<float>(size_t(w) * h * 3)};
  for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = linear[data.get()[i]];
  return image;
}

}  // namespace wavebake
