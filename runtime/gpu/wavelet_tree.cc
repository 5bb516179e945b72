#include "runtime/gpu/wavelet_tree.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "core/products/haar_tree.h"
#include "core/util/parallel_for.h"
#include "runtime/gpu/tree_stream.h"

namespace wavebake {
namespace {

static_assert(std::endian::native == std::endian::little, "the texture files are little-endian");

// One face's row, dense in Mallat layout (face-local y·N + x).
void FaceRow(const SampleRows& rows, int cell, int face, std::vector<float>& out) {
  const int per_face = rows.light_res() * rows.light_res();
  out.assign(per_face, 0.0f);
  const auto terms = rows.terms(cell, face);
  const auto values = rows.values(cell, face);
  for (size_t k = 0; k < terms.size(); ++k) out[terms[k] - face * per_face] = values[k];
}

// The three coefficients of every square of a face, each square's largest
// magnitude, and its significance: what §4.4 compares with the cut-off, the
// magnitude × 2^(−level_weight·l) (the importance-weighted variant; 0:
// Boulton's rule as written).
struct FaceSquares {
  std::vector<std::array<float, 3>> c;
  std::vector<float> significance;
};
void SquaresOfFace(int n, const std::vector<float>& row, double level_weight, FaceSquares& out) {
  const int squares = haar::SquaresOf(n);
  out.c.resize(squares);
  out.significance.resize(squares);
  for (int l = 0; l < haar::LevelsOf(n); ++l) {
    const float weight = static_cast<float>(std::exp2(-level_weight * l));
    for (int sy = 0; sy < (1 << l); ++sy) {
      for (int sx = 0; sx < (1 << l); ++sx) {
        const int id = haar::SquareId(l, sx, sy);
        float m = 0;
        for (int t = 0; t < 3; ++t) {
          out.c[id][t] = row[haar::FaceIndex(n, l, t, sx, sy)];
          m = std::max(m, std::fabs(out.c[id][t]));
        }
        out.significance[id] = m * weight;
      }
    }
  }
}

// Energy histogram by log2 |c|max, 16 bins an octave: the cut-off of a
// target error is a bin edge, so nodes below it are exactly whole bins.
constexpr int kBinsPerOctave = 16, kBins = 4096, kBinZero = 2048;
int BinOf(float m) {
  if (!(m > 0)) return 0;
  const int b = static_cast<int>(std::floor(std::log2(m) * kBinsPerOctave)) + kBinZero;
  return std::clamp(b, 1, kBins - 1);
}
double BinEdge(int b) { return std::exp2(double(b - kBinZero) / kBinsPerOctave); }

// Cells in fixed chunks, merged in chunk order: the result does not depend
// on the number of threads.
constexpr int kChunks = 64;

std::vector<uint8_t> Kept(int n, const FaceSquares& sq, double cut_off) {
  std::vector<uint8_t> significant(sq.c.size());
  for (size_t s = 0; s < sq.c.size(); ++s) significant[s] = sq.significance[s] >= cut_off;
  return KeepLive(n, significant);
}

// Energy of the nodes the rule prunes at `cut_off` (a node below the
// cut-off with a significant descendant is kept).
double PrunedEnergy(const SampleRows& rows, const SampleSet& samples, double cut_off,
                    double level_weight) {
  const int n = rows.light_res(), cells = rows.cells();
  std::vector<double> lost(kChunks, 0.0);
  ParallelFor(kChunks, [&](int chunk) {
    std::vector<float> row;
    FaceSquares sq;
    for (int cell = chunk * cells / kChunks; cell < (chunk + 1) * cells / kChunks; ++cell) {
      if (samples.grid[cell] < 0) continue;
      for (int face = 0; face < 6; ++face) {
        FaceRow(rows, cell, face, row);
        SquaresOfFace(n, row, level_weight, sq);
        const std::vector<uint8_t> kept = Kept(n, sq, cut_off);
        for (size_t s = 0; s < sq.c.size(); ++s)
          if (!kept[s])
            for (float v : sq.c[s]) lost[chunk] += double{v} * v;
      }
    }
  });
  double sum = 0;
  for (double l : lost) sum += l;
  return sum;
}

// The largest bin edge whose pruning loses at most target² of the rows'
// energy: the histogram gives a cut-off that is safe counting only
// significance (ancestors kept for a descendant only keep more), then
// bisection over the bins above it, since the pruned energy grows with the
// cut-off.
double CutOffFor(const SampleRows& rows, const SampleSet& samples, double target,
                 double level_weight) {
  const int n = rows.light_res();
  std::vector<std::vector<double>> hist(kChunks, std::vector<double>(kBins, 0.0));
  std::vector<double> total(kChunks, 0.0);
  const int cells = rows.cells();
  ParallelFor(kChunks, [&](int chunk) {
    std::vector<float> row;
    FaceSquares sq;
    for (int cell = chunk * cells / kChunks; cell < (chunk + 1) * cells / kChunks; ++cell) {
      if (samples.grid[cell] < 0) continue;
      for (int face = 0; face < 6; ++face) {
        FaceRow(rows, cell, face, row);
        total[chunk] += double{row[0]} * row[0];
        SquaresOfFace(n, row, level_weight, sq);
        for (size_t s = 0; s < sq.c.size(); ++s) {
          double e = 0;
          for (float v : sq.c[s]) e += double{v} * v;
          hist[chunk][BinOf(sq.significance[s])] += e;
          total[chunk] += e;
        }
      }
    }
  });
  std::vector<double> merged(kBins, 0.0);
  double energy_total = 0;
  for (int c = 0; c < kChunks; ++c) {
    energy_total += total[c];
    for (int b = 0; b < kBins; ++b) merged[b] += hist[c][b];
  }
  const double budget = target * target * energy_total;
  double below = 0;  // energy of bins < b
  int b = 1;
  for (; b < kBins; ++b) {  // bin 0, exact zeros, is pruned at any positive cut-off
    if (below + merged[b] > budget) break;
    below += merged[b];
  }
  int lo = std::min(b, kBins - 1), hi = kBins;  // lo is safe; hi is past every bin
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (PrunedEnergy(rows, samples, BinEdge(mid), level_weight) <= budget)
      lo = mid;
    else
      hi = mid;
  }
  return BinEdge(lo);
}

// The step minifloat (header "conventions.steps"): code 0 is a zero step,
// code s > 0 is (1 + (s mod 8)/8) · 2^(s div 8 − bias).
float StepOf(int code, int bias) {
  if (code == 0) return 0.0f;
  return static_cast<float>(std::ldexp(1.0 + (code & 7) / 8.0, (code >> 3) - bias));
}
// The smallest code whose step is ≥ s (> 0), at least 1, at most 255.
int StepCodeAtLeast(float s, int bias) {
  int lo = 1, hi = 255;
  if (StepOf(hi, bias) < s) return hi;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (StepOf(mid, bias) >= s)
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

int Quantize(float c, float step, int max_code) {
  const float q = std::nearbyint(c / step);
  return static_cast<int>(std::clamp(q, -float(max_code), float(max_code)));
}

// One tree's units (one 4-bit value a byte) and its block entry.
struct TreeOut {
  std::vector<uint8_t> units;
  float scaling = 0;
  int64_t kept = 0, jumps = 0;
  double pruned = 0, quantized = 0;
  bool jump_overflow = false;  // a subtree of 2^16 units or more (N > 256)
};

void Put(std::vector<uint8_t>& units, uint64_t value, int count) {
  for (int k = 0; k < count; ++k) units.push_back(static_cast<uint8_t>((value >> (4 * k)) & 15u));
}

struct TreeParams {
  int n = 0, levels = 0, bias = 0, jump_nodes = 0;
  double cut_off = 0, level_weight = 0;
  std::vector<int> bits, nibbles;
};

void BuildTree(const TreeParams& p, const std::vector<float>& row, FaceSquares& sq, TreeOut& out) {
  SquaresOfFace(p.n, row, p.level_weight, sq);
  const std::vector<uint8_t> kept = Kept(p.n, sq, p.cut_off);
  out.scaling = row[0];
  for (size_t s = 0; s < sq.c.size(); ++s)
    if (!kept[s])
      for (float v : sq.c[s]) out.pruned += double{v} * v;
  const std::vector<TreeNode> nodes = DepthFirstNodes(p.n, kept);
  if (nodes.empty()) return;
  out.kept = static_cast<int64_t>(nodes.size());

  // One step per level: among the steps of the minifloat at and below the
  // window's (largest kept |c| / max code), spanning three octaves, the one
  // with the least squared error over the level's kept coefficients (a few
  // large coefficients may clamp when that lets the many small ones round
  // finer).
  std::vector<int> step_code(p.levels, 0);
  std::vector<float> step(p.levels, 0.0f);
  for (int l = 0; l < p.levels; ++l) {
    const int max_code = (1 << (p.bits[l] - 1)) - 1;
    float window = 0;
    for (const TreeNode& node : nodes)
      if (node.level == l)
        for (float v : sq.c[node.square]) window = std::max(window, std::fabs(v));
    if (!(window > 0)) continue;
    auto error = [&](float s) {
      double e = 0;
      for (const TreeNode& node : nodes)
        if (node.level == l)
          for (float v : sq.c[node.square]) {
            const double d = double{Quantize(v, s, max_code) * s} - v;
            e += d * d;
          }
      return e;
    };
    const int first = StepCodeAtLeast(window / static_cast<float>(max_code), p.bias);
    int best = first;
    double best_error = error(StepOf(first, p.bias));
    for (int code = first - 1; code >= std::max(1, first - 24); --code) {
      const double e = error(StepOf(code, p.bias));
      if (e < best_error) best_error = e, best = code;
    }
    step_code[l] = best;
    step[l] = StepOf(best, p.bias);
  }

  // Units of each node (record and jump), then its subtree's, by prefix sums
  // over the depth-first order.
  const size_t count = nodes.size();
  std::vector<uint8_t> jump(count, 0);
  std::vector<int64_t> prefix(count + 1, 0);
  for (size_t i = 0; i < count; ++i) {
    const TreeNode& node = nodes[i];
    jump[i] = node.level >= 1 && node.level <= p.levels - 3 && node.child_mask != 0 &&
              node.descendants >= p.jump_nodes;
    prefix[i + 1] = prefix[i] + p.nibbles[node.level] + (jump[i] ? 4 : 0);
  }
  out.units.reserve(2 * p.levels + prefix[count]);
  for (int l = 0; l < p.levels; ++l) Put(out.units, static_cast<uint64_t>(step_code[l]), 2);
  for (size_t i = 0; i < count; ++i) {
    const TreeNode& node = nodes[i];
    const int b = p.bits[node.level];
    const int max_code = (1 << (b - 1)) - 1;
    uint64_t record = 0;
    for (int t = 0; t < 3; ++t) {
      const float v = sq.c[node.square][t];
      int q = 0;
      if (step[node.level] > 0) q = Quantize(v, step[node.level], max_code);
      const double d = double{q * step[node.level]} - v;
      out.quantized += d * d;
      record |= static_cast<uint64_t>(q + (1 << (b - 1))) << (t * b);
    }
    if (node.level < p.levels - 1) record |= uint64_t{node.child_mask} << (3 * b);
    if (jump[i]) record |= uint64_t{1} << (3 * b + 4);
    Put(out.units, record, p.nibbles[node.level]);
    if (jump[i]) {
      ++out.jumps;
      // From the node's first unit to the first unit past its subtree: a
      // level-1 subtree at N = 256 with 9-bit codes is under 41 000 units.
      const int64_t span = prefix[i + 1 + node.descendants] - prefix[i];
      out.jump_overflow |= span > 0xFFFF;
      Put(out.units, static_cast<uint64_t>(span), 4);
    }
  }
}

}  // namespace

std::vector<int> DefaultCodeBits(int levels) {
  std::vector<int> bits(levels, 9);
  const int finest[3] = {4, 5, 6};
  for (int k = 0; k < 3 && k < levels; ++k) bits[levels - 1 - k] = finest[k];
  return bits;
}

absl::StatusOr<std::vector<int>> ParseCodeBits(const std::string& spec) {
  std::vector<int> bits;
  if (spec == "auto") return bits;
  for (absl::string_view part : absl::StrSplit(spec, ',')) {
    int b = 0;
    if (!absl::SimpleAtoi(part, &b))
      return absl::InvalidArgumentError(absl::StrCat(
          "bits: '", spec, "' is not auto, a number of bits or one per level (9,9,6,5,4)"));
    bits.push_back(b);
  }
  return bits;
}

int RecordNibbles(int level, int levels, int bits) {
  const int b = 3 * bits + (level < levels - 1 ? 4 : 0) + (level < levels - 2 ? 1 : 0);
  return (b + 3) / 4;
}

absl::StatusOr<WaveletTreeTextures> BuildWaveletTrees(const SampleRows& rows,
                                                      const SampleSet& samples,
                                                      const WaveletTreeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.cut_off < 0 && !(options.target_error >= 0))
    return absl::InvalidArgumentError("target_error: must be ≥ 0 when no cut-off is given");
  if (!std::isfinite(options.cut_off))
    return absl::InvalidArgumentError("cut_off: not a finite number");
  if (!(options.level_weight >= -4 && options.level_weight <= 8))
    return absl::InvalidArgumentError("level_weight: not in [-4, 8]");
  if (options.jump_nodes < 1)
    return absl::InvalidArgumentError(
        absl::StrCat("jump_nodes: ", options.jump_nodes, " is not ≥ 1"));
  if (rows.width() != samples.width || rows.height() != samples.height ||
      static_cast<int>(samples.grid.size()) != rows.cells())
    return absl::InvalidArgumentError("samples: grid differs from the transport's");
  if (rows.light_res() < 2)
    return absl::InvalidArgumentError(
        absl::StrCat("light_res: ", rows.light_res(), " has no wavelet level"));
  const int n = rows.light_res(), levels = haar::LevelsOf(n);
  std::vector<int> bits = options.bits;
  if (bits.empty()) bits = DefaultCodeBits(levels);
  if (bits.size() == 1) bits.assign(levels, bits[0]);
  if (static_cast<int>(bits.size()) != levels)
    return absl::InvalidArgumentError(absl::StrCat("bits: ", bits.size(), " values for ", levels,
                                                   " levels (give one, or one per level)"));
  for (int b : bits)
    if (b < kMinCodeBits || b > kMaxCodeBits)
      return absl::InvalidArgumentError(
          absl::StrCat("bits: ", b, " is not in [", kMinCodeBits, ", ", kMaxCodeBits, "]"));

  WaveletTreeTextures t;
  t.width = rows.width();
  t.height = rows.height();
  t.light_res = n;
  t.levels = levels;
  t.code_bits = bits;
  t.default_bits = options.bits.empty();
  for (int l = 0; l < levels; ++l) t.record_nibbles.push_back(RecordNibbles(l, levels, bits[l]));
  t.level_weight = options.level_weight;
  t.jump_nodes = options.jump_nodes;
  if (options.cut_off >= 0) {
    t.cut_off = options.cut_off;
  } else {
    t.target_error = options.target_error;
    t.cut_off = CutOffFor(rows, samples, options.target_error, options.level_weight);
  }

  // The step bias: every step is at most the largest |c| (a window over the
  // smallest max code, 1), and the largest step of the minifloat with this
  // bias, 1.875 · 2^(31 − bias), exceeds it.
  const int cells = rows.cells();
  float largest = 0;
  for (int cell = 0; cell < cells; ++cell)
    if (samples.grid[cell] >= 0)
      for (int face = 0; face < 6; ++face)
        for (float v : rows.values(cell, face)) largest = std::max(largest, std::fabs(v));
  t.step_bias = largest > 0 ? std::clamp(30 - std::ilogb(largest), -96, 126) : 0;

  TreeParams p{.n = n,
               .levels = levels,
               .bias = t.step_bias,
               .jump_nodes = options.jump_nodes,
               .cut_off = t.cut_off,
               .level_weight = options.level_weight,
               .bits = bits,
               .nibbles = t.record_nibbles};
  std::vector<std::array<TreeOut, 6>> trees(cells);
  std::vector<double> chunk_energy(kChunks, 0.0);
  ParallelFor(kChunks, [&](int chunk) {
    std::vector<float> row;
    FaceSquares sq;
    for (int cell = chunk * cells / kChunks; cell < (chunk + 1) * cells / kChunks; ++cell) {
      if (samples.grid[cell] < 0) continue;
      for (int face = 0; face < 6; ++face) {
        FaceRow(rows, cell, face, row);
        for (float v : row) chunk_energy[chunk] += double{v} * v;
        BuildTree(p, row, sq, trees[cell][face]);
      }
    }
  });

  // Pack: trees in (sampled cell, face) order, each right after the last.
  int64_t units = 0;
  for (int cell = 0; cell < cells; ++cell) {
    if (samples.grid[cell] < 0) continue;
    ++t.sampled;
    for (int face = 0; face < 6; ++face) {
      units += static_cast<int64_t>(trees[cell][face].units.size());
      if (trees[cell][face].jump_overflow)
        return absl::InvalidArgumentError(absl::StrCat(
            "light_res: ", n, " gives subtrees a 16-bit jump cannot span; raise jump_nodes"));
    }
  }
  if (units >= (int64_t{1} << 31))
    return absl::ResourceExhaustedError(
        absl::StrCat("line: ", units, " units exceed 2^31; raise the cut-off"));
  t.line_nibbles = units;
  t.line_texels = (units + 7) / 8 + 1;  // one spare texel: the shader reads two at a time
  t.line.assign(4 * WaveletTreeTextures::RowsFor(t.line_texels) * kTreeLineWidth, 0);
  const int64_t blocks = 6 * t.sampled;
  t.blocks.assign(2 * WaveletTreeTextures::RowsFor(blocks) * kTreeLineWidth, 0u);
  t.cells.assign(4 * static_cast<size_t>(cells), 0.0f);
  double energy = 0;
  for (int c = 0; c < kChunks; ++c) energy += chunk_energy[c];
  t.stats.energy_total = energy;
  int64_t at = 0, rank = 0;
  for (int cell = 0; cell < cells; ++cell) {
    const int32_t sample = samples.grid[cell];
    if (sample < 0) continue;
    const Vec3 a = samples.albedo[sample];
    std::copy_n(std::array<float, 4>{a.x, a.y, a.z, static_cast<float>(1 + rank)}.data(), 4,
                &t.cells[4 * size_t(cell)]);
    for (int face = 0; face < 6; ++face) {
      TreeOut& tree = trees[cell][face];
      uint32_t* b = &t.blocks[2 * size_t(6 * rank + face)];
      b[0] = tree.units.empty() ? 0xFFFFFFFFu : static_cast<uint32_t>(at);
      b[1] = std::bit_cast<uint32_t>(tree.scaling);
      for (uint8_t u : tree.units) {
        t.line[at / 2] |= static_cast<uint8_t>(u << (4 * (at & 1)));
        ++at;
      }
      ++t.stats.trees;
      t.stats.empty_trees += tree.units.empty();
      t.stats.nodes_total += haar::SquaresOf(n);
      t.stats.nodes_kept += tree.kept;
      t.stats.jumps += tree.jumps;
      t.stats.energy_pruned += tree.pruned;
      t.stats.energy_quantized += tree.quantized;
      std::vector<uint8_t>().swap(tree.units);
    }
    ++rank;
  }
  t.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

}  // namespace wavebake
