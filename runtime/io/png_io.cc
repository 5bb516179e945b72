// PNG half of image_io.h.
#include <cmath>
#include <vector>

#include "absl/strings/str_cat.h"
#include "runtime/io/image_io.h"
#include "runtime/io/stb_codecs.h"
#include "runtime/io/tonemap.h"
#include "storage/files/atomic_file.h"

namespace wavebake {

absl::StatusOr<std::vector<std::byte>> EncodePng(int width, int height, std::span<const float> rgb,
                                                 float exposure_stops, Vec3 background) {
  if (width <= 0 || height <= 0 || rgb.size() != size_t(width) * height * 3) {
    return absl::InvalidArgumentError(absl::StrCat("image ", width, "x", height, " needs ",
                                                   size_t(width) * height * 3, " floats, got ",
                                                   rgb.size()));
  }
  const float scale = std::exp2(exposure_stops);
  std::vector<uint8_t> pixels(rgb.size());
  for (size_t i = 0; i < rgb.size(); i += 3) {
    const auto c = ToneMapPixel({rgb[i], rgb[i + 1], rgb[i + 2]}, scale, background);
    pixels[i] = c[0], pixels[i + 1] = c[1], pixels[i + 2] = c[2];
  }
  return EncodePng(width, height, 3, pixels);
}

absl::Status WritePng(const std::filesystem::path& path, int width, int height,
                      std::span<const float> rgb, float exposure_stops, Vec3 background) {
  absl::StatusOr<std::vector<std::byte>> png =
      EncodePng(width, height, rgb, exposure_stops, background);
  if (!png.ok())
    return absl::Status(png.status().code(),
                        absl::StrCat(path.string(), ": ", png.status().message()));
  return AtomicWriteFile(path, *png);
}

}  // namespace wavebake
