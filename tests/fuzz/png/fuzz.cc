// PNG bytes through the private stb_image (runtime/io/stb_codecs.h): no crash,
// no endless loop, and a decoded image has the size it says.
#include "runtime/io/stb_codecs.h"
#include "tests/fuzz/fuzz_util.h"

namespace wavebake::fuzz {

std::vector<std::string> Seeds() {
  std::vector<std::string> seeds;
  for (auto [w, h] : {std::pair{1, 1}, {7, 3}, {32, 2}}) {
    std::vector<uint8_t> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>(i * 29);
    absl::StatusOr<std::vector<std::byte>> png = EncodePng(w, h, 3, rgb);
    if (png.ok()) seeds.emplace_back(reinterpret_cast<const char*>(png->data()), png->size());
  }
  return seeds;
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using wavebake::fuzz::Require;
  const auto bytes = std::as_bytes(std::span(reinterpret_cast<const char*>(data), size));
  absl::StatusOr<wavebake::Rgb8Image> image = wavebake::DecodePng(bytes, "f.png");
  if (!image.ok()) {
    Require(image.status().message().find("f.png") != std::string::npos, "error names the file");
    return 0;
  }
  Require(image->width > 0 && image->height > 0, "positive size");
  Require(image->rgb.size() == size_t(image->width) * image->height * 3, "3 bytes per pixel");
  return 0;
}
