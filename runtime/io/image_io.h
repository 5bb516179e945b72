#pragma once
// Image and mesh outputs of `wavebake relight` (DESIGN.md §5) and the EXR
// reader behind LoadEnvMap. Every write is atomic (storage/files/atomic_file.h).
#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "core/util/vec3.h"
#include "runtime/env/env_map.h"

namespace wavebake {

// rgb: [height * width * 3] linear floats, row-major, row 0 at the top.
// Written losslessly as 32-bit float R, G, B channels (ZIP compression);
// NaN (masked) pixels are kept as NaN.
absl::Status WriteExr(const std::filesystem::path& path, int width, int height,
                      std::span<const float> rgb);

// Reads R, G, B (or a luminance-only Y, copied to all three) of any scanline
// or tiled OpenEXR file as float, whatever the stored pixel type. The image
// may have any size; LoadEnvMap checks layouts.
absl::StatusOr<EnvMap> ReadExrImage(const std::filesystem::path& path);
// The same from the file's bytes; `name` names it in errors. The header is
// checked before OpenEXR reads it (runtime/io/exr_preflight.h).
absl::StatusOr<EnvMap> DecodeExr(std::span<const std::byte> file, const std::string& name);
// Radiance RGBE (.hdr) through stb_image, linear float.
absl::StatusOr<EnvMap> ReadHdrImage(const std::filesystem::path& path);
// An 8-bit PNG through stb_image, sRGB decoded to linear [0, 1].
absl::StatusOr<EnvMap> ReadPngImage(const std::filesystem::path& path);

// 8-bit sRGB PNG: linear × 2^exposure_stops, clamped to [0, 1], sRGB OETF.
// A pixel with any NaN channel (a masked cell) gets `background`, a linear
// colour in [0, 1] encoded the same way but not exposed.
absl::Status WritePng(const std::filesystem::path& path, int width, int height,
                      std::span<const float> rgb, float exposure_stops, Vec3 background);
// The same PNG as bytes (for embedding, e.g. in a glTF).
absl::StatusOr<std::vector<std::byte>> EncodePng(int width, int height, std::span<const float> rgb,
                                                 float exposure_stops, Vec3 background);
// 8-bit pixels (channels 1..4, rows top first) as the bytes of a PNG file.
absl::StatusOr<std::vector<std::byte>> EncodePng(int width, int height, int channels,
                                                 std::span<const uint8_t> pixels);

// Binary little-endian PLY: vertices with float x, y, z and uchar red, green,
// blue (tone-mapped as in WritePng, NaN → black), faces as `list uchar int
// vertex_indices`. rgb_per_vertex: [positions.size() * 3] linear floats.
absl::Status WritePlyVertexColors(const std::filesystem::path& path,
                                  std::span<const Vec3> positions,
                                  std::span<const std::array<uint32_t, 3>> triangles,
                                  std::span<const float> rgb_per_vertex, float exposure_stops);

// The scene's meshes concatenated in order (vertex ids offset by the vertex
// counts of the meshes before, as in samples/vertex).
absl::Status WritePlyVertexColors(const std::filesystem::path& path, const Scene& scene,
                                  std::span<const float> rgb_per_vertex, float exposure_stops);

}  // namespace wavebake
