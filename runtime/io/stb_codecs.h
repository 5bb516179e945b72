#pragma once
// Radiance .hdr and PNG through Debian's stb_image / stb_image_write (the
// libstb-dev headers), compiled into this library with internal linkage
// (STB_IMAGE_STATIC): libdraco, which assimp pulls in, exports its own copy
// of every stbi_* function, and calls by those public names resolved to it
// rather than to Debian's libstb. Nothing else in the project calls stb.
//
// Decoding never runs past its input: a truncated or corrupt file is
// InvalidArgument naming `name` (see stb_codecs.cc for how stb is kept from
// looping at the end of the data).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "runtime/env/env_map.h"

namespace wavebake {

// RGBE pixels → linear RGB floats, any size (LoadEnvMap checks layouts).
absl::StatusOr<EnvMap> DecodeRadianceHdr(std::span<const std::byte> file, const std::string& name);
// Linear RGB floats → a run-length encoded Radiance file.
absl::StatusOr<std::vector<std::byte>> EncodeRadianceHdr(int width, int height,
                                                         std::span<const float> rgb);

struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // [height * width * 3], row 0 at the top
};
absl::StatusOr<Rgb8Image> DecodePng(std::span<const std::byte> file, const std::string& name);
// 8-bit pixels (channels 1..4, rows top first); image_io.h declares it too.
absl::StatusOr<std::vector<std::byte>> EncodePng(int width, int height, int channels,
                                                 std::span<const uint8_t> pixels);

}  // namespace wavebake
