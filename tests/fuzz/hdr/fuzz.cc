// Radiance .hdr bytes through the private stb_image (runtime/io/stb_codecs.h):
// no crash, no endless loop (libFuzzer's -timeout), and a decoded image has
// the size it says.
#include <cmath>

#include "runtime/io/stb_codecs.h"
#include "tests/fuzz/fuzz_util.h"

namespace wavebake::fuzz {

std::vector<std::string> Seeds() {
  std::vector<std::string> seeds;
  for (auto [w, h] : {std::pair{4, 2}, {16, 4}, {9, 1}}) {
    std::vector<float> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < rgb.size(); ++i)
      rgb[i] = std::ldexp(1.0f + float(i % 5), int(i % 9) - 4);
    absl::StatusOr<std::vector<std::byte>> hdr = EncodeRadianceHdr(w, h, rgb);
    if (hdr.ok()) seeds.emplace_back(reinterpret_cast<const char*>(hdr->data()), hdr->size());
  }
  seeds.push_back("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n\x80\x80\x80\x81");
  return seeds;
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using wavebake::fuzz::Require;
  const auto bytes = std::as_bytes(std::span(reinterpret_cast<const char*>(data), size));
  absl::StatusOr<wavebake::EnvMap> env = wavebake::DecodeRadianceHdr(bytes, "f.hdr");
  if (!env.ok()) {
    Require(env.status().message().find("f.hdr") != std::string::npos, "error names the file");
    return 0;
  }
  Require(env->width > 0 && env->height > 0, "positive size");
  Require(env->rgb.size() == size_t(env->width) * env->height * 3, "3 floats per pixel");
  for (float v : env->rgb) Require(std::isfinite(v) && v >= 0, "RGBE decodes to finite >= 0");
  return 0;
}
