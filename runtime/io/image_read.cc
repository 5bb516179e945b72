// Image readers of image_io.h on the project's private stb_image
// (runtime/io/stb_codecs.h: truncated or corrupt files are errors naming them).
#include <cmath>

#include "runtime/io/image_io.h"
#include "runtime/io/stb_codecs.h"
#include "storage/files/atomic_file.h"

namespace wavebake {

absl::StatusOr<EnvMap> ReadHdrImage(const std::filesystem::path& path) {
  absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(path);
  if (!bytes.ok()) return bytes.status();
  return DecodeRadianceHdr(*bytes, path.string());
}

absl::StatusOr<EnvMap> ReadPngImage(const std::filesystem::path& path) {
  absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(path);
  if (!bytes.ok()) return bytes.status();
  absl::StatusOr<Rgb8Image> png = DecodePng(*bytes, path.string());
  if (!png.ok()) return png.status();
  // The sRGB EOTF (IEC 61966-2-1), once per code.
  float linear[256];
  for (int i = 0; i < 256; ++i) {
    const double c = i / 255.0;
    linear[i] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
  }
  EnvMap image{png->width, png->height, std::vector<float>(png->rgb.size())};
  for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = linear[png->rgb[i]];
  return image;
}

}  // namespace wavebake
