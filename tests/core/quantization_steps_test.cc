// The step choice of FINALIZE (core/columns/quantization_steps.h) on hand-made
// columns: the uniform rule's budget arithmetic and its int16 fallback.
#include "core/columns/quantization_steps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/columns/column_coding.h"
#include "core/columns/quantizer.h"

namespace wavebake {
namespace {

BakeParams Auto(double target) {
  BakeParams p;
  p.target_error = target;
  return p;  // bits auto, uniform, matrix scope: the defaults
}

// Three ordinary columns: 100 kept coefficients each (U = 100/12), |v| ≤ 1.
std::vector<ColumnQuantInput> Ordinary() {
  return std::vector<ColumnQuantInput>(
      3, {.max_abs = 1.0, .step_unit = 100.0 / 12, .reference_energy = 50.0});
}

TEST(QuantizationStepsTest, UniformStepSpendsExactlyTheHalfBudget) {
  const std::vector<ColumnQuantInput> cols = Ordinary();
  const StepPlan plan = PlanSteps(cols, Auto(0.01));
  // (t/2)²·ΣE = 2.5e-5·150 = 3.75e-3 = Δ²·300/12  →  Δ = sqrt(1.5e-4).
  const double delta = std::sqrt(0.25 * 1e-4 * 150 / (300.0 / 12));
  EXPECT_NEAR(plan.step, delta, 1e-7 * delta);
  EXPECT_LE(plan.step, delta);  // rounded down, never over budget
  for (float s : plan.steps) EXPECT_EQ(s, static_cast<float>(plan.step));
  EXPECT_EQ(plan.overflow_columns, 0);
  EXPECT_EQ(plan.max_code, kMaxStoredCode);
  EXPECT_LE(plan.expected_energy, plan.budget);
  EXPECT_GT(plan.expected_energy, plan.budget * (1 - 1e-6));
}

// A column whose max/Δ exceeds int16 takes max/32767 of its own; the others
// share a Δ solved again for what that column left, so the sum still fits.
TEST(QuantizationStepsTest, Int16OverflowColumnTakesItsOwnCoarserStep) {
  std::vector<ColumnQuantInput> cols = Ordinary();
  const double delta0 = PlanSteps(cols, Auto(0.01)).step;
  cols.push_back(
      {.max_abs = 3 * kMaxStoredCode * delta0, .step_unit = 1.0 / 12, .reference_energy = 50.0});
  const StepPlan plan = PlanSteps(cols, Auto(0.01));
  EXPECT_EQ(plan.overflow_columns, 1);
  EXPECT_EQ(plan.steps[3], StepForMax(cols[3].max_abs, kMaxStoredCode));
  EXPECT_GT(plan.steps[3], plan.step);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(plan.steps[c], static_cast<float>(plan.step));
  EXPECT_LE(plan.expected_energy, plan.budget * (1 + 1e-9));
  // Quantizing the overflow column with its step fits int16 and stays within
  // half a step.
  const std::vector<float> v = {static_cast<float>(cols[3].max_abs),
                                static_cast<float>(-cols[3].max_abs), 0.5f};
  const std::vector<uint32_t> pos = {0, 1, 2};
  const std::vector<uint8_t> lv = {0, 0, 0};
  const auto q = Quantize(v, pos, lv, LevelScaling::kUniform, plan.steps[3], kMaxStoredCode, 1, 3);
  std::vector<float> back(3);
  Dequantize(q, pos, lv, LevelScaling::kUniform, plan.steps[3], 1, 3, back);
  for (size_t i = 0; i < v.size(); ++i) {
    EXPECT_LE(std::abs(q[i]), kMaxStoredCode);
    EXPECT_LE(std::fabs(double(back[i]) - v[i]),
              QuantizationBound(plan.steps[3], 0, LevelScaling::kUniform));
  }
}

TEST(QuantizationStepsTest, FixedBitsNormalizeEachColumnByItsMax) {
  std::vector<ColumnQuantInput> cols = Ordinary();
  cols[1].max_abs = 0.25;
  BakeParams p = Auto(0.01);
  p.bits = 8;
  const StepPlan plan = PlanSteps(cols, p);
  EXPECT_EQ(plan.bits, 8);
  EXPECT_EQ(plan.max_code, 127);
  EXPECT_EQ(plan.steps[0], StepForMax(1.0, 127));
  EXPECT_EQ(plan.steps[1], StepForMax(0.25, 127));
}

TEST(QuantizationStepsTest, EmptyColumnsGetNoStep) {
  std::vector<ColumnQuantInput> cols = Ordinary();
  cols.push_back({});  // nothing kept
  const StepPlan plan = PlanSteps(cols, Auto(0.01));
  EXPECT_EQ(plan.steps[3], 0.0f);
  EXPECT_GT(plan.steps[0], 0.0f);
}

// bits_needed is the fewest b in [2, 16) whose dither energy Σ (max_c/Q_b)²·U_c
// fits the half budget (16 if none does), against a scan of every b in long
// double with unrounded steps. Targets from 4 down to 1e-6 take it from 2
// to "none fits"; each case's budget stays clear of every sum by 1e-5 so that
// the float steps' rounding cannot tip the comparison.
TEST(QuantizationStepsTest, BitsNeededIsTheFewestThatFitsAtEveryTarget) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> log_max(-6, 0), kept(1, 400);
  std::vector<ColumnQuantInput> cols(300);
  for (ColumnQuantInput& c : cols) {
    c.max_abs = std::pow(10.0, log_max(rng));
    c.step_unit = kept(rng) / 12;
    c.reference_energy = c.max_abs * c.max_abs * kept(rng) / 4;
  }
  std::vector<int> seen;
  for (double target = 4.0; target > 1e-6; target /= 1.7) {
    long double budget = 0;
    for (const ColumnQuantInput& c : cols) budget += 0.25L * target * target * c.reference_energy;
    int expected = 16;
    for (int b = 15; b >= 2; --b) {
      const long double q = std::ldexp(1.0L, b - 1) - 1;
      long double e = 0;
      for (const ColumnQuantInput& c : cols) e += c.max_abs * c.max_abs / (q * q) * c.step_unit;
      ASSERT_GT(std::fabs(e - budget), 1e-5L * budget) << "target " << target << ", b " << b;
      if (e <= budget) expected = b;
    }
    EXPECT_EQ(PlanSteps(cols, Auto(target)).bits_needed, expected) << "target " << target;
    seen.push_back(expected);
  }
  EXPECT_EQ(seen.front(), 2);
  EXPECT_EQ(seen.back(), 16);
}

}  // namespace
}  // namespace wavebake
