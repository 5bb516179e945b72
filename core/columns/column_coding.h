#pragma once
// The per-column math of TRANSFORM_COLUMNS, free of any I/O (DESIGN.md §1
// "Column transform", "Coefficient selection", "Scaling and quantization";
// 4D paper §4.2–4.3): pick the column's transform depth, select its kept
// coefficients, and work out how many quantization bits it would need.
#include <cstdint>
#include <span>
#include <vector>

#include "core/bake/bake_params.h"
#include "core/columns/quantizer.h"
#include "core/columns/uncovered_fill.h"

namespace wavebake {

// What every column of one job shares.
struct ColumnCodingParams {
  int width = 0, height = 0;  // the sample grid: a column is a W×H image
  WaveletFilter filter = WaveletFilter::kHaar;
  ColumnMode mode = ColumnMode::kAdaptive;
  double target_error = 0.01;
  ErrorScope scope = ErrorScope::kMatrix;
  int column_terms = 0;      // > 0: keep a fixed K per column instead of the target
  double matrix_energy = 0;  // mean column energy of the whole matrix (scope matrix)
  LevelScaling level_scaling = LevelScaling::kUniform;
  int bits = 0;       // --bits: 0 = auto
  uint64_t seed = 1;  // --seed: the quantizer's dither (core/columns/quantizer.h)
  // Fills the uncovered cells before a transform of depth ≥ 1 (core/columns/uncovered_fill.h);
  // null: they stay 0. Not owned.
  const CellFiller* filler = nullptr;
};

ColumnCodingParams MakeColumnCodingParams(const BakeParams& params, int width, int height,
                                          double matrix_energy);

// One column after selection, before quantization (FINALIZE quantizes once the
// matrix-wide bit count is known).
struct CodedColumn {
  int depth = 0;
  std::vector<uint32_t> positions;  // y*W + x in the depth-`depth` Mallat layout, increasing
  std::vector<float> values;        // the kept coefficients, parallel to positions
  double energy = 0;                // Σ of the column's squared staged values
  double reference_energy = 0;      // E_ref: matrix_energy, or `energy` for scope column
  double dropped_energy = 0;        // Σ (c_i·w_i)² over dropped coefficients
  // max_i |v_i / k_i| (core/columns/quantizer.h): the column's step Δ reaches its
  // largest code C when Δ = max_abs / C.
  double max_abs = 0;
  // Σ_i (k_i·w_i)²/12 over kept coefficients: the expected energy of the
  // subtractive-dither quantization error per unit step (multiply by Δ²).
  double step_unit = 0;
  int min_bits = 2;  // fewest bits b with Δ = max_abs/Q_b meeting the column's own budget
};

// No coding at all (depth −1): CodeColumn's `flat` when it codes none.
inline CodedColumn NoCoding() {
  CodedColumn c;
  c.depth = -1;
  return c;
}

// Codes one W×H column image (row-major, staged values). `left_out` is energy
// the column already lost before coding (bounced light not added,
// worker/columns/column_bounces.h): it is spent from the column's budget,
// so the selection drops at most budget − left_out, and is counted in
// dropped_energy. Not thread-safe across threads sharing `out`; reuses
// per-thread scratch buffers.
// With `flat` and ComparesCodedSize(p), a column whose coding is not at
// depth 0 also gets its depth-0 coding there (the same budget; `2d`'s coding
// of it), for adaptive by size (core/columns/group_codings.h), unless it
// keeps over twice the coefficients; otherwise flat->depth is −1.
void CodeColumn(const ColumnCodingParams& p, std::span<const float> image, CodedColumn* out,
                double left_out = 0, CodedColumn* flat = nullptr);

// CodeColumn without the depth search: the coding at `depth` (an update's
// recomputed column at its old depth, worker/columns/local_columns.h), with
// `left_out` spent as CodeColumn spends it. An empty column, or one that
// fits its budget whole, keeps nothing at the depth CodeColumn records for it.
void CodeColumnAtDepth(const ColumnCodingParams& p, std::span<const float> image, int depth,
                       CodedColumn* out, double left_out = 0);

// Whether a job compares codings by size: adaptive with a target and
// --level-scaling uniform (a step per level would need its own estimate).
bool ComparesCodedSize(const ColumnCodingParams& p);

// The ranking weights of a depth-d layout (core/wavelets/subband.h synthesis norms);
// empty means all ones (core/columns/nla.h), as for the orthonormal filters.
std::span<const float> RankingWeights(const ColumnCodingParams& p, int depth);

// SubbandAt(x, y, W, H, depth).level of every position y*W + x, computed once
// per thread and shape (the l of the quantizer's level factor k = 2^−l).
const std::vector<uint8_t>& SubbandLevels(int width, int height, int depth);

// The quantization half of the error budget: (target/2)²·E_ref (DESIGN.md §1).
double QuantizationBudget(double target_error, double reference_energy);
// Expected quantization error energy of a column quantized to `bits` with its
// max normalized to Q_b (subtractive dither: variance Δ²/12 per kept
// coefficient, weighted like the selection): (max_abs/Q_b)²·step_unit.
double QuantizationEnergy(double max_abs, double step_unit, int bits);
// The fewest b in 2..16 with QuantizationEnergy(max_abs, step_unit, b) ≤
// `allowed`; 16 if none is enough.
int MinBitsFor(double max_abs, double step_unit, double allowed);

}  // namespace wavebake
