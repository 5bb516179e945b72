#pragma once
// FINALIZE's choice of every column's quantization step Δ_c (the store's
// `scale`; DESIGN.md §1 "Scaling and quantization", core/columns/quantizer.h). The
// expected subtractive-dither error energy of column c is Δ_c²·U_c with
// U_c = Σ_i (k_i·w_i)²/12 (core/columns/column_coding.h), and the quantization half
// of the budget is (target/2)²·E_ref.
//
//  * --bits B (any scaling): the paper's rule, Δ_c = max_c / Q_B — every
//    column's largest value gets the largest B-bit code.
//  * --bits auto, --level-scaling paper: the same with the fewest matrix-wide
//    b whose summed Δ_c²·U_c fits the matrix budget (column scope: the max
//    over columns of each column's own need).
//  * --bits auto, --level-scaling uniform ("error-budgeted"): one
//    matrix-wide absolute step Δ with Σ_c Δ²·U_c = (target/2)²·Σ E_ref. For a
//    sum of squared errors under a total budget, equal steps are the
//    high-rate optimum (each coefficient's distortion-rate slope is then the
//    same); a per-column max normalization gives weak columns a tiny absolute
//    step they do not need. A column needs only as many bits as max_c/Δ. A
//    column with max_c/Δ > 32767 (int16) takes its own coarser step
//    max_c/32767; Δ is then solved again for the remaining budget, so the sum
//    still fits. Column scope: the same per column with its own budget.
#include <cstdint>
#include <span>
#include <vector>

#include "core/bake/bake_params.h"

namespace wavebake {

struct ColumnQuantInput {
  double max_abs = 0;    // max_i |v_i / k_i|
  double step_unit = 0;  // U_c
  double reference_energy = 0;
  int min_bits = 2;  // the column's own need with max normalization
};

struct StepPlan {
  std::vector<float> steps;      // Δ_c per column (0: nothing to quantize)
  int max_code = 0;              // clamp of every code: Q_b, or 32767 for uniform auto
  int bits = 0;                  // b of the max-normalized rules; 0 for uniform auto
  int bits_needed = 0;           // what --bits auto would pick with max normalization
  int max_column_bits = 2;       // the largest single column's need with max normalization
  double step = 0;               // uniform auto, matrix scope: the matrix-wide Δ
  int64_t overflow_columns = 0;  // uniform auto: columns that took a coarser step of their own
  double expected_energy = 0;    // Σ_c Δ_c²·U_c
  double budget = 0;             // Σ_c (target/2)²·E_ref,c
};

StepPlan PlanSteps(std::span<const ColumnQuantInput> columns, const BakeParams& params);

}  // namespace wavebake
