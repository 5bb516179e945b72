#pragma once
// A diffuse store's transport rows as wavelet-tree textures for a GPU
// (Boulton §4.4–4.5), the value behind `wavebake export --format
// wavelet-tree`. Per sample and cube face one pruned Haar tree of the row
// (runtime/gpu/tree_stream.h: §4.4's sibling-group pruning, §4.5's depth-first
// line with jump nodes), coefficients quantized per tree to 8 or 16 bits,
// all trees packed into one line texture; a block texture (one texel per
// sample and face, Boulton's sub-block texture) holds each tree's offset,
// length, scaling coefficient and quantization step; a cell texture the
// albedo. WaveletTreeHeader documents every array for a third-party loader.
//
// The rows come from the 4D store through SampleRows (runtime/relight/sample_rows.h):
// every column image through its inverse column transform, transposed.
#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "nlohmann/json.hpp"
#include "runtime/relight/sample_rows.h"

namespace wavebake {

inline constexpr char kWaveletTreeFormat[] = "wavebake-wavelet-tree/1";
// Texels per row of every line texture: WebGL2's guaranteed minimum
// MAX_TEXTURE_SIZE, so any WebGL2 device can upload them.
inline constexpr int kTreeLineWidth = 2048;

struct WaveletTreeOptions {
  // ≥ 0: the absolute cut-off of §4.4 (a node is significant when one of its
  // three coefficients has |c| ≥ cut_off, in the units of T's row
  // coefficients); < 0: chosen from target_error.
  double cut_off = -1;
  // Relative L2 error of the pruned rows: the largest cut-off (to 1/16 of an
  // octave) whose pruned nodes, sibling rule included, hold at most
  // target_error² of the rows' energy.
  double target_error = 0.02;
  int bits = 8;  // 8 or 16
  // The importance-weighted variant of §4.4's rule: a node of level l
  // (0 = the whole face) is significant when max |c| · 2^(−level_weight·l)
  // ≥ cut_off. 0 is the rule as written. The lighting's terms are chosen by
  // area-weighted magnitude (runtime/relight/lighting.h), so they sit
  // mostly at coarse levels, where a transfer node then matters most.
  double level_weight = 0;
};

struct WaveletTreeTextures {
  int width = 0, height = 0, light_res = 0, bits = 8;
  double cut_off = 0;
  double target_error = -1;  // the one asked for, −1 when cut_off was given
  double level_weight = 0;
  // RGBA texels, line_width per row, raw little-endian: bits/8 bytes a channel.
  int64_t line_texels = 0;
  std::vector<uint8_t> line;
  // [cells·6 texels, padded to whole rows] × RGBA uint32: offset, length,
  // float bits of the scaling coefficient, float bits of the step.
  std::vector<uint32_t> blocks;
  // [cells] × RGBA float32: albedo RGB, 1 sampled / 0 masked.
  std::vector<float> cells;
  struct Stats {
    int64_t trees = 0, nodes_total = 0, nodes_kept = 0, jumps = 0;
    double energy_total = 0, energy_pruned = 0;  // Σ c² of the rows, of the pruned nodes
    double seconds = 0;
  } stats;

  int bias() const { return bits == 8 ? 128 : 32768; }
  int max_code() const { return bits == 8 ? 127 : 32767; }
  static int64_t RowsFor(int64_t texels) { return (texels + kTreeLineWidth - 1) / kTreeLineWidth; }
  size_t bytes() const { return line.size() + blocks.size() * 4 + cells.size() * 4; }
};

// Errors: bits not 8 or 16, a negative target with no cut-off, rows of
// another grid than samples, light_res < 2.
absl::StatusOr<WaveletTreeTextures> BuildWaveletTrees(const SampleRows& rows,
                                                      const SampleSet& samples,
                                                      const WaveletTreeOptions& options);

// The JSON header: every array's file, type, shape and meaning, the
// conventions (face order, Mallat positions, line order, codes, decode
// formula), the settings and the statistics. `source` is recorded as given.
nlohmann::json WaveletTreeHeader(const WaveletTreeTextures& t, const nlohmann::json& source);

}  // namespace wavebake
