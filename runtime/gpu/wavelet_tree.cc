#include "runtime/gpu/wavelet_tree.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>

#include "absl/strings/str_cat.h"
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
// magnitude (the quantization window), and its significance: what §4.4
// compares with the cut-off, the magnitude × 2^(−level_weight·l) (the
// importance-weighted variant; 0: Boulton's rule as written).
struct FaceSquares {
  std::vector<std::array<float, 3>> c;
  std::vector<float> max_abs, significance;
};
void SquaresOfFace(int n, const std::vector<float>& row, double level_weight, FaceSquares& out) {
  const int squares = haar::SquaresOf(n);
  out.c.resize(squares);
  out.max_abs.resize(squares);
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
        out.max_abs[id] = m;
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

// Energy of the nodes §4.4's rule prunes at `cut_off`, the sibling rule
// included (a node below the cut-off whose sibling group survives is kept).
double PrunedEnergy(const SampleRows& rows, const SampleSet& samples, double cut_off,
                    double level_weight) {
  const int n = rows.light_res(), cells = rows.cells();
  std::vector<double> lost(kChunks, 0.0);
  ParallelFor(kChunks, [&](int chunk) {
    std::vector<float> row;
    FaceSquares sq;
    std::vector<uint8_t> significant;
    for (int cell = chunk * cells / kChunks; cell < (chunk + 1) * cells / kChunks; ++cell) {
      if (samples.grid[cell] < 0) continue;
      for (int face = 0; face < 6; ++face) {
        FaceRow(rows, cell, face, row);
        SquaresOfFace(n, row, level_weight, sq);
        significant.resize(sq.c.size());
        for (size_t s = 0; s < sq.c.size(); ++s) significant[s] = sq.significance[s] >= cut_off;
        const std::vector<uint8_t> kept = KeepSiblingGroups(n, significant);
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

// The largest bin edge whose pruning, sibling rule included, loses at most
// target² of the rows' energy: the histogram gives a cut-off that is safe
// without the sibling rule (which only keeps more), then bisection over the
// bins above it, since the pruned energy grows with the cut-off.
double CutOffFor(const SampleRows& rows, const SampleSet& samples, double target,
                 double level_weight, double& energy_total) {
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
  energy_total = 0;
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

// One tree's texels (RGBA codes) and its block entry.
struct TreeOut {
  std::vector<uint16_t> codes;  // 4 per texel
  float scaling = 0, step = 0;
  int64_t kept = 0, jumps = 0;
  double pruned = 0;
};

void BuildTree(int n, const std::vector<float>& row, double cut_off, double level_weight,
               int max_code, int bias, int bits, FaceSquares& sq, TreeOut& out) {
  SquaresOfFace(n, row, level_weight, sq);
  std::vector<uint8_t> significant(sq.c.size());
  for (size_t s = 0; s < sq.c.size(); ++s) significant[s] = sq.significance[s] >= cut_off;
  const std::vector<uint8_t> kept = KeepSiblingGroups(n, significant);
  const std::vector<TreeRecord> line = DepthFirstLine(n, kept);
  float max_abs = 0;
  for (size_t s = 0; s < sq.c.size(); ++s) {
    if (kept[s]) {
      max_abs = std::max(max_abs, sq.max_abs[s]);
      ++out.kept;
    } else {
      for (float v : sq.c[s]) out.pruned += double{v} * v;
    }
  }
  // Per-tree window (§4.4 quantizes "windowed" coefficients): the largest
  // kept magnitude maps to the largest code.
  out.scaling = row[0];
  out.step = max_abs > 0 ? max_abs / static_cast<float>(max_code) : 0.0f;
  out.codes.clear();
  const uint32_t mask = (1u << bits) - 1;
  for (const TreeRecord& r : line) {
    if (r.jump) {
      ++out.jumps;
      const uint32_t off = static_cast<uint32_t>(r.offset);
      out.codes.insert(out.codes.end(),
                       {uint16_t(off & mask), uint16_t(off >> bits), uint16_t(r.next_code), 0});
      continue;
    }
    for (int t = 0; t < 3; ++t) {
      const float q = out.step > 0 ? std::nearbyint(sq.c[r.square][t] / out.step) : 0.0f;
      const int code = static_cast<int>(std::clamp(q, -float(max_code), float(max_code)));
      out.codes.push_back(static_cast<uint16_t>(code + bias));
    }
    out.codes.push_back(static_cast<uint16_t>(r.next_code));
  }
}

}  // namespace

absl::StatusOr<WaveletTreeTextures> BuildWaveletTrees(const SampleRows& rows,
                                                      const SampleSet& samples,
                                                      const WaveletTreeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.bits != 8 && options.bits != 16)
    return absl::InvalidArgumentError(absl::StrCat("bits: ", options.bits, " is not 8 or 16"));
  if (options.cut_off < 0 && !(options.target_error >= 0))
    return absl::InvalidArgumentError("target_error: must be ≥ 0 when no cut-off is given");
  if (!std::isfinite(options.cut_off))
    return absl::InvalidArgumentError("cut_off: not a finite number");
  if (!(options.level_weight >= -4 && options.level_weight <= 8))
    return absl::InvalidArgumentError("level_weight: not in [-4, 8]");
  if (rows.width() != samples.width || rows.height() != samples.height ||
      static_cast<int>(samples.grid.size()) != rows.cells())
    return absl::InvalidArgumentError("samples: grid differs from the transport's");
  if (rows.light_res() < 2)
    return absl::InvalidArgumentError(
        absl::StrCat("light_res: ", rows.light_res(), " has no wavelet level"));

  WaveletTreeTextures t;
  t.width = rows.width();
  t.height = rows.height();
  t.light_res = rows.light_res();
  t.bits = options.bits;
  t.level_weight = options.level_weight;
  const int n = t.light_res;
  if (options.cut_off >= 0) {
    t.cut_off = options.cut_off;
  } else {
    t.target_error = options.target_error;
    t.cut_off =
        CutOffFor(rows, samples, options.target_error, options.level_weight, t.stats.energy_total);
  }

  const int cells = rows.cells();
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
        BuildTree(n, row, t.cut_off, options.level_weight, t.max_code(), t.bias(), t.bits, sq,
                  trees[cell][face]);
      }
    }
  });

  // Pack: trees in (cell, face) order.
  const int64_t blocks = int64_t{cells} * 6;
  t.blocks.assign(4 * WaveletTreeTextures::RowsFor(blocks) * kTreeLineWidth, 0u);
  t.cells.assign(4 * static_cast<size_t>(cells), 0.0f);
  int64_t texels = 0;
  for (int cell = 0; cell < cells; ++cell) {
    for (int face = 0; face < 6; ++face) texels += trees[cell][face].codes.size() / 4;
  }
  t.line_texels = texels;
  const int bytes_per = t.bits / 8;
  t.line.assign(4 * bytes_per * WaveletTreeTextures::RowsFor(texels) * kTreeLineWidth, 0);
  int64_t at = 0;
  double energy = 0;
  for (int c = 0; c < kChunks; ++c) energy += chunk_energy[c];
  t.stats.energy_total = energy;
  for (int cell = 0; cell < cells; ++cell) {
    const int32_t sample = samples.grid[cell];
    if (sample >= 0) {
      const Vec3 a = samples.albedo[sample];
      std::copy_n(std::array<float, 4>{a.x, a.y, a.z, 1.0f}.data(), 4, &t.cells[4 * size_t(cell)]);
    }
    for (int face = 0; face < 6; ++face) {
      TreeOut& tree = trees[cell][face];
      const int64_t len = static_cast<int64_t>(tree.codes.size() / 4);
      uint32_t* b = &t.blocks[4 * (size_t(cell) * 6 + face)];
      b[0] = static_cast<uint32_t>(at);
      b[1] = static_cast<uint32_t>(len);
      b[2] = std::bit_cast<uint32_t>(tree.scaling);
      b[3] = std::bit_cast<uint32_t>(tree.step);
      if (bytes_per == 1) {
        for (size_t k = 0; k < tree.codes.size(); ++k)
          t.line[4 * at + k] = static_cast<uint8_t>(tree.codes[k]);
      } else if (!tree.codes.empty()) {  // memcpy from an empty vector's null data() is UB
        std::memcpy(&t.line[8 * at], tree.codes.data(), tree.codes.size() * 2);
      }
      at += len;
      if (sample >= 0) {
        ++t.stats.trees;
        t.stats.nodes_total += haar::SquaresOf(n);
        t.stats.nodes_kept += tree.kept;
        t.stats.jumps += tree.jumps;
        t.stats.energy_pruned += tree.pruned;
      }
      std::vector<uint16_t>().swap(tree.codes);
    }
  }
  t.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

nlohmann::json WaveletTreeHeader(const WaveletTreeTextures& t, const nlohmann::json& source) {
  using nlohmann::json;
  const int64_t blocks = int64_t{t.width} * t.height * 6;
  const char* line_type = t.bits == 8 ? "uint8" : "uint16";
  json h;
  h["format"] = kWaveletTreeFormat;
  h["source"] = source;
  h["width"] = t.width;
  h["height"] = t.height;
  h["light_res"] = t.light_res;
  h["levels"] = haar::LevelsOf(t.light_res);
  h["bits"] = t.bits;
  h["bias"] = t.bias();
  h["cut_off"] = t.cut_off;
  if (t.target_error >= 0) h["target_error"] = t.target_error;
  h["level_weight"] = t.level_weight;
  h["line"] = {{"file", "line.bin"},
               {"texels", t.line_texels},
               {"width", kTreeLineWidth},
               {"height", WaveletTreeTextures::RowsFor(t.line_texels)},
               {"type", line_type},
               {"channels", 4},
               {"webgl", t.bits == 8 ? "RGBA8UI / RGBA_INTEGER / UNSIGNED_BYTE"
                                     : "RGBA16UI / RGBA_INTEGER / UNSIGNED_SHORT"},
               {"meaning",
                "the trees' records, texel k at (k mod width, k div width); rows past "
                "`texels` are zero padding"}};
  h["blocks"] = {{"file", "blocks.bin"},
                 {"texels", blocks},
                 {"width", kTreeLineWidth},
                 {"height", WaveletTreeTextures::RowsFor(blocks)},
                 {"type", "uint32"},
                 {"channels", 4},
                 {"webgl", "RGBA32UI / RGBA_INTEGER / UNSIGNED_INT"},
                 {"meaning",
                  "texel b = cell·6 + face (cell = y·width + x): R first line texel of the "
                  "tree, G its texels (0: no wavelet node), B the scaling coefficient "
                  "(float32 bits), A the quantization step (float32 bits)"}};
  h["cells"] = {{"file", "cells.bin"},
                {"texels", int64_t{t.width} * t.height},
                {"width", t.width},
                {"height", t.height},
                {"type", "float32"},
                {"channels", 4},
                {"webgl", "RGBA32F / RGBA / FLOAT"},
                {"meaning",
                 "texel (x, y) = cell y·width + x, row 0 = the grid's row 0 (the top "
                 "of the image): albedo RGB, A 1 sampled / 0 masked"}};
  h["conventions"] = {
      {"faces", "+X -X +Y -Y +Z -Z, OpenGL cube map orientation, N x N texels each"},
      {"row",
       "per face the 2D non-standard orthonormal Haar transform of the N x N row "
       "of T, full depth, Mallat layout (scaling coefficient at (0,0))"},
      {"node",
       "square (l, sx, sy), 0 <= sx, sy < 2^l, l = 0..levels-1: its coefficients "
       "type 0 at Mallat (2^l+sx, sy), type 1 at (sx, 2^l+sy), type 2 at "
       "(2^l+sx, 2^l+sy)"},
      {"pruning",
       "Boulton 4.4, importance-weighted by level: a node of level l is significant "
       "when max |c| * 2^(-level_weight * l) >= cut_off (level_weight 0: the rule "
       "as written); a node is kept when it or a descendant is significant, and the "
       "four children of a node are kept together"},
      {"order",
       "depth first from the root (0,0,0); children (2sx,2sy), (2sx+1,2sy), "
       "(2sx,2sy+1), (2sx+1,2sy+1)"},
      {"node_texel",
       "R, G, B = codes of types 0, 1, 2; A = level+1 of the next node of the "
       "tree in line order (0: the tree ends)"},
      {"jump_texel",
       "follows every node whose A-1 is greater than its level (its children "
       "follow): offset = R + G * 2^bits texels from the node to the first "
       "texel after its subtree; B = level+1 of the node there (0: the tree "
       "ends); A = 0"},
      {"decode", "c = (code - bias) * step; step and the scaling coefficient from the block"},
      {"relight",
       "B(cell) = albedo * sum over faces of (S_face * L_scaling + sum over kept "
       "nodes of c . L) with L the lighting's coefficients in the same basis"}};
  h["stats"] = {
      {"trees", t.stats.trees},
      {"nodes_total", t.stats.nodes_total},
      {"nodes_kept", t.stats.nodes_kept},
      {"jumps", t.stats.jumps},
      {"rel_error_pruned",
       t.stats.energy_total > 0 ? std::sqrt(t.stats.energy_pruned / t.stats.energy_total) : 0.0},
      {"bytes", t.bytes()},
      {"seconds", t.stats.seconds}};
  return h;
}

}  // namespace wavebake
