#pragma once
// A diffuse store's transport rows as wavelet-tree textures for a GPU
// (Boulton §4.4–4.5), the value behind `wavebake export --format
// wavelet-tree`. Per sampled cell and cube face one pruned Haar tree of the
// row (runtime/gpu/tree_stream.h: significant nodes and their ancestors, each
// node with a child mask), its nodes packed depth-first into one line of 4-bit
// units: a node's record is three quantized coefficients (per-level code
// bits, fewest at the finest level), its child mask and a jump flag, and
// §4.5's jump record follows only nodes whose subtree is long enough to be
// worth skipping in one step (the shader scans short ones). Each tree's
// coefficients are quantized with one step per level (an 8-bit minifloat at
// the head of the tree), so fine levels use the whole code range instead of
// a window set by the coarsest node. A block texture (one 8-byte texel per
// sampled cell and face) holds where each tree starts and its scaling
// coefficient; the cell texture holds the albedo and which block row a cell
// uses. WaveletTreeHeader documents every array for a third-party loader.
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

inline constexpr char kWaveletTreeFormat[] = "wavebake-wavelet-tree/2";
// Texels per row of the line and block textures: WebGL2's guaranteed
// minimum MAX_TEXTURE_SIZE, so any WebGL2 device can upload them.
inline constexpr int kTreeLineWidth = 2048;
// The default target error of the pruned rows (WaveletTreeOptions).
inline constexpr double kDefaultTreeTargetError = 0.035;
// Code bits a level may have: a record (three codes, a child mask, a jump
// flag) must fit in the 32 bits the shader reads at once.
inline constexpr int kMinCodeBits = 2, kMaxCodeBits = 9;

struct WaveletTreeOptions {
  // ≥ 0: the absolute cut-off of §4.4 (a node is significant when one of its
  // three coefficients has |c| ≥ cut_off, in the units of T's row
  // coefficients); < 0: chosen from target_error.
  double cut_off = -1;
  // Relative L2 error of the pruned rows: the largest cut-off (to 1/16 of an
  // octave) whose pruned nodes hold at most target_error² of the rows' energy
  // (quantization not counted).
  double target_error = kDefaultTreeTargetError;
  // Code bits per level, level 0 first: empty = DefaultCodeBits; one value =
  // every level; else one per level. Each in [kMinCodeBits, kMaxCodeBits].
  std::vector<int> bits;
  // The importance-weighted variant of §4.4's rule: a node of level l
  // (0 = the whole face) is significant when max |c| · 2^(−level_weight·l)
  // ≥ cut_off. 0 is the rule as written.
  double level_weight = 0;
  // A node of level 1..levels−3 carries a jump record when at least this
  // many kept nodes lie below it (≥ 1). Below level levels−3 a subtree holds
  // at most four nodes, which the shader reads faster than a jump.
  int jump_nodes = 16;
};

// The default code bits of a face with `levels` wavelet levels: 4 at the
// finest, 5 and 6 at the next two, 9 above. Fine levels hold most nodes;
// coarse ones few, whose coefficients meet the largest lighting terms of
// smooth skies (a 5-bit code at level 0 or 1 alone adds 0.35 points under
// builtin:sky); 9 bits fill the 32-bit record 8 bits would round up to.
std::vector<int> DefaultCodeBits(int levels);
// 4-bit units of a node record at `level`: three codes, a child mask below
// the finest level, a jump flag above level levels−2, rounded up.
int RecordNibbles(int level, int levels, int bits);
// WaveletTreeOptions::bits from text: "auto" (empty), "B" (every level) or
// "B0,B1,..." (level 0 first). Range and count are checked by
// BuildWaveletTrees; errors here (not numbers) name `bits`.
absl::StatusOr<std::vector<int>> ParseCodeBits(const std::string& spec);

struct WaveletTreeTextures {
  int width = 0, height = 0, light_res = 0, levels = 0;
  std::vector<int> code_bits, record_nibbles;  // per level
  int step_bias = 0;  // of the step minifloat (WaveletTreeHeader "conventions.steps")
  double cut_off = 0;
  double target_error = -1;  // the one asked for, −1 when cut_off was given
  double level_weight = 0;
  int jump_nodes = 0;
  bool default_bits = true;  // code_bits from DefaultCodeBits
  int64_t sampled = 0;       // cells with a sample: blocks = 6 · sampled
  // The line: 4-bit units, unit u in byte u/2 (low half when u is even);
  // RGBA8UI texels, kTreeLineWidth a row; one spare zero texel at least.
  int64_t line_nibbles = 0, line_texels = 0;
  std::vector<uint8_t> line;
  // RG32UI texels, [6 · sampled, padded to whole rows] × 2: the first unit
  // of the tree (0xFFFFFFFF: no wavelet node) and the scaling coefficient's
  // float bits.
  std::vector<uint32_t> blocks;
  // [cells] × RGBA float32: albedo RGB, A = 0 masked or 1 + the cell's rank
  // among the sampled cells.
  std::vector<float> cells;
  struct Stats {
    int64_t trees = 0, empty_trees = 0, nodes_total = 0, nodes_kept = 0, jumps = 0;
    // Σ c² of the rows, of the pruned nodes, and Σ (ĉ − c)² of the kept ones.
    double energy_total = 0, energy_pruned = 0, energy_quantized = 0;
    double seconds = 0;
  } stats;

  static int64_t RowsFor(int64_t texels) { return (texels + kTreeLineWidth - 1) / kTreeLineWidth; }
  size_t bytes() const { return line.size() + blocks.size() * 4 + cells.size() * 4; }
};

// Errors: bits out of range or not one per level, a negative target with no
// cut-off, jump_nodes < 1, rows of another grid than samples, light_res < 2.
absl::StatusOr<WaveletTreeTextures> BuildWaveletTrees(const SampleRows& rows,
                                                      const SampleSet& samples,
                                                      const WaveletTreeOptions& options);

// The JSON header: every array's file, type, shape and meaning, the
// conventions (face order, Mallat positions, line order, records, steps,
// decode and relight formulas), the settings and the statistics. `source`
// is recorded as given.
nlohmann::json WaveletTreeHeader(const WaveletTreeTextures& t, const nlohmann::json& source);

}  // namespace wavebake
