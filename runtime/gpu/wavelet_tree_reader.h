#pragma once
// A reader of `wavebake export --format wavelet-tree` directories written
// only from the header's documented conventions (runtime/gpu/wavelet_tree.h's
// WaveletTreeHeader), sharing no code with the exporter's tree walk
// (runtime/gpu/tree_stream.h) nor with the shader: the oracle the round-trip and
// GPU tests compare against. It rebuilds each tree's row coefficients from
// its depth-first line, checking the line's structure as it goes (sibling
// groups complete, jump offsets landing past their subtrees, levels in
// range), and relights by a dense dot product per face.
//
// Hostile input is refused with an error naming the field: the header's
// values and shapes, the files' sizes, every block's range, every record.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "nlohmann/json.hpp"

namespace wavebake {

class WaveletTreeReader {
 public:
  // DIR/header.json and the files it names (inside DIR, plain names only).
  static absl::StatusOr<WaveletTreeReader> Open(const std::filesystem::path& dir);
  // The same from memory: the header and the three arrays' bytes.
  static absl::StatusOr<WaveletTreeReader> Parse(const nlohmann::json& header,
                                                 std::vector<uint8_t> line,
                                                 std::vector<uint8_t> blocks,
                                                 std::vector<uint8_t> cells);

  int width() const { return width_; }
  int height() const { return height_; }
  int light_res() const { return n_; }
  int bits() const { return bits_; }
  bool sampled(int cell) const { return cells_[4 * size_t(cell) + 3] != 0; }
  // Quantization step of tree (cell, face): every decoded coefficient is
  // within step/2 of the value it was made from.
  float step(int cell, int face) const;

  // The row of (cell, face): N² coefficients, Mallat layout (y·N + x), zero
  // where pruned. Parsed on every call.
  absl::Status DecodeRow(int cell, int face, std::span<float> row) const;

  // B per cell = albedo · Σ_face row · L_face, lighting as
  // LightingCoefficients::rgb ([3·6N²], row basis); [W·H·3], NaN masked.
  // magnitude (optional): albedo · Σ |row_j · L_j| per cell and channel, the
  // size of the sum that bounds its float rounding.
  absl::StatusOr<std::vector<float>> Relight(std::span<const float> lighting_rgb,
                                             std::vector<float>* magnitude = nullptr) const;

 private:
  int width_ = 0, height_ = 0, n_ = 0, levels_ = 0, bits_ = 8, bias_ = 128;
  int64_t line_texels_ = 0;
  std::vector<uint16_t> line_;    // 4 codes a texel
  std::vector<uint32_t> blocks_;  // 4 a block
  std::vector<float> cells_;      // 4 a cell
};

}  // namespace wavebake
