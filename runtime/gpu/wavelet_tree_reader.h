#pragma once
// A reader of `wavebake export --format wavelet-tree` directories written
// only from the header's documented conventions (runtime/gpu/wavelet_tree.h's
// WaveletTreeHeader), sharing no code with the exporter's tree walk
// (runtime/gpu/tree_stream.h) nor with the shader: the oracle the round-trip and
// GPU tests compare against. Opening it checks every field of the header,
// every cell and block, and walks every tree's records (codes in range,
// child masks only below the finest level, no bits past a record's fields,
// jumps landing past their subtrees, each tree ending where the next
// begins); it rebuilds a tree's row coefficients from its records and
// relights by a dense dot product per face.
//
// Hostile input is refused with an error naming the field: the header's
// values and shapes, the files' sizes, every cell, block and record.
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
  int levels() const { return levels_; }
  const std::vector<int>& code_bits() const { return bits_; }
  bool sampled(int cell) const { return cells_[4 * size_t(cell) + 3] != 0; }

  // The row of (cell, face) of a sampled cell: N² coefficients, Mallat
  // layout (y·N + x), zero where pruned. steps (optional): the tree's
  // quantization step per level (every decoded coefficient of level l is a
  // whole multiple of steps[l]). present (optional): N² flags, 1 where the
  // tree holds the coefficient (the scaling one always).
  absl::Status DecodeRow(int cell, int face, std::span<float> row,
                         std::vector<float>* steps = nullptr,
                         std::vector<uint8_t>* present = nullptr) const;

  // B per cell = albedo · Σ_face row · L_face, lighting as
  // LightingCoefficients::rgb ([3·6N²], row basis); [W·H·3], NaN masked.
  // magnitude (optional): albedo · Σ |row_j · L_j| per cell and channel, the
  // size of the sum that bounds its float rounding.
  absl::StatusOr<std::vector<float>> Relight(std::span<const float> lighting_rgb,
                                             std::vector<float>* magnitude = nullptr) const;

 private:
  // Walks tree `b` (a block index) up to unit `limit`, writing its
  // coefficients into row (N²) and its steps if given, and where it ends
  // into end; checks every record.
  absl::Status Walk(int64_t b, int64_t limit, float* row, std::vector<float>* steps, int64_t* end,
                    uint8_t* present = nullptr) const;
  uint64_t Field(int64_t unit, int bits) const;

  int width_ = 0, height_ = 0, n_ = 0, levels_ = 0, step_bias_ = 0;
  int64_t sampled_ = 0, units_ = 0;
  std::vector<int> bits_, record_units_;
  std::vector<uint8_t> line_;
  std::vector<uint32_t> blocks_;   // 2 a block
  std::vector<int64_t> tree_end_;  // per block: the unit past its tree
  std::vector<float> cells_;       // 4 a cell
};

}  // namespace wavebake
