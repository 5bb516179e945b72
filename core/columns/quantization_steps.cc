#include "core/columns/quantization_steps.h"

#include <algorithm>
#include <cmath>

#include "core/columns/column_coding.h"
#include "core/columns/quantizer.h"

namespace wavebake {
namespace {

// The largest float ≤ x: a step rounded down never spends more than its budget.
float FloorToFloat(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, 0.0f);
  return f;
}

double SumEnergy(std::span<const ColumnQuantInput> cols, std::span<const float> steps) {
  double e = 0;
  for (size_t c = 0; c < cols.size(); ++c) e += double{steps[c]} * steps[c] * cols[c].step_unit;
  return e;
}

void MaxNormalized(std::span<const ColumnQuantInput> cols, int bits, StepPlan* plan) {
  plan->bits = bits;
  plan->max_code = MaxQuantCode(bits);
  for (size_t c = 0; c < cols.size(); ++c)
    plan->steps[c] = StepForMax(cols[c].max_abs, plan->max_code);
}

double MatrixEnergy(std::span<const ColumnQuantInput> cols, int bits) {
  double e = 0;
  for (const ColumnQuantInput& c : cols) e += QuantizationEnergy(c.max_abs, c.step_unit, bits);
  return e;
}

// The fewest b in [2, 16] whose matrix-wide Σ_c (max_c/Q_b)²·U_c fits the
// budget (16 if none below does), by bisection: each term falls as b grows
// (a larger Q_b, a smaller step, rounded and squared monotonically), and so
// does their sum in a fixed order, rounding included, so the first fit is
// the one a scan from b = 2 finds, in 4 passes over the columns instead of
// up to 14 (each pass is one StepForMax per column: at N = 128 the scan was
// 4 % of a refined bake's CPU, once per FINALIZE task).
int MatrixBits(std::span<const ColumnQuantInput> cols, double budget) {
  int lo = 2, hi = 16;  // the answer lies in [lo, hi]; hi needs no check
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (MatrixEnergy(cols, mid) <= budget)
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

// Uniform auto, matrix scope: Δ for the budget left after the int16-overflow
// columns took their own steps, repeated until no further column overflows
// (each round only lowers Δ, so at most M rounds; in practice one or two).
void UniformMatrix(std::span<const ColumnQuantInput> cols, double budget, StepPlan* plan) {
  std::vector<bool> own(cols.size(), false);
  double delta = 0;
  for (;;) {
    double rest = budget, unit = 0;
    for (size_t c = 0; c < cols.size(); ++c) {
      if (own[c]) {
        const double s = StepForMax(cols[c].max_abs, kMaxStoredCode);
        rest -= s * s * cols[c].step_unit;
      } else {
        unit += cols[c].step_unit;
      }
    }
    delta = unit > 0 && rest > 0 ? std::sqrt(rest / unit) : 0;
    bool grew = false;
    for (size_t c = 0; c < cols.size(); ++c) {
      if (!own[c] && cols[c].max_abs > 0 && cols[c].max_abs > delta * kMaxStoredCode) {
        own[c] = true;
        grew = true;
      }
    }
    if (!grew || delta == 0) break;
  }
  plan->step = FloorToFloat(delta);
  for (size_t c = 0; c < cols.size(); ++c) {
    if (cols[c].max_abs == 0) continue;
    const float own_step = StepForMax(cols[c].max_abs, kMaxStoredCode);
    plan->steps[c] = std::max(static_cast<float>(plan->step), own_step);
    plan->overflow_columns += own_step > plan->step;
  }
}

// Uniform auto, column scope: each column's own budget.
void UniformColumns(std::span<const ColumnQuantInput> cols, double target, StepPlan* plan) {
  for (size_t c = 0; c < cols.size(); ++c) {
    if (cols[c].max_abs == 0 || cols[c].step_unit == 0) continue;
    const double allowed = QuantizationBudget(target, cols[c].reference_energy);
    const float budgeted = FloorToFloat(std::sqrt(allowed / cols[c].step_unit));
    const float own_step = StepForMax(cols[c].max_abs, kMaxStoredCode);
    plan->steps[c] = std::max(budgeted, own_step);
    plan->overflow_columns += own_step > budgeted;
  }
}

}  // namespace

StepPlan PlanSteps(std::span<const ColumnQuantInput> cols, const BakeParams& params) {
  StepPlan plan;
  plan.steps.assign(cols.size(), 0.0f);
  for (const ColumnQuantInput& c : cols) {
    plan.max_column_bits = std::max(plan.max_column_bits, c.min_bits);
    plan.budget += QuantizationBudget(params.target_error, c.reference_energy);
  }
  const bool column_scope = params.error_scope == ErrorScope::kColumn;
  plan.bits_needed = column_scope ? plan.max_column_bits : MatrixBits(cols, plan.budget);
  if (params.bits != 0) {
    MaxNormalized(cols, params.bits, &plan);
  } else if (params.level_scaling == LevelScaling::kPaper) {
    MaxNormalized(cols, plan.bits_needed, &plan);
  } else {
    plan.max_code = kMaxStoredCode;
    if (column_scope)
      UniformColumns(cols, params.target_error, &plan);
    else
      UniformMatrix(cols, plan.budget, &plan);
  }
  plan.expected_energy = SumEnergy(cols, plan.steps);
  return plan;
}

}  // namespace wavebake
