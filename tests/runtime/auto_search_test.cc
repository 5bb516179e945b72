// The policy of `bake --auto` (runtime/auto/auto_search.h) against a synthetic
// error model with the shape the real pipeline has: e_disc(N) = a/N (the
// cubemap's discretization error falls with N), e_comp = k·target (the
// compression error follows the column target), bytes ∝ N²/target.
#include "runtime/auto/auto_search.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace wavebake {
namespace {

using ::testing::HasSubstr;

struct Model {
  double a = 0.4;        // e_disc(N) = a / N
  double k = 0.5;        // e_comp = k · column target
  int stubborn_res = 0;  // at this N, e_comp = 0.05 whatever the target
  double cliff = 1e9;    // above this target, e_comp = 0.05
  double EDisc(int n) const { return a / n; }
  double EComp(int n, double target) const {
    return n == stubborn_res || target > cliff ? 0.05 : k * target;
  }
};

// Drives the search to its end as the orchestration does; counts the steps.
struct Driven {
  AutoSearch search;
  AutoAction last;
  int disc_measurements = 0, bakes = 0;
};

Driven Drive(const AutoSearchConfig& config, const Model& model) {
  Driven d{AutoSearch(config), {}, 0, 0};
  for (int guard = 0; guard < 100; ++guard) {
    d.last = d.search.Next();
    if (d.last.step == AutoStep::kMeasureDisc) {
      ++d.disc_measurements;
      d.search.OnDisc(model.EDisc(d.last.light_res));
    } else if (d.last.step == AutoStep::kBake) {
      ++d.bakes;
      const double e_disc = model.EDisc(d.last.light_res), t = d.last.column_target;
      const double e_comp = model.EComp(d.last.light_res, t);
      d.search.OnBaked({.bits = 10,
                        .bytes = static_cast<int64_t>(d.last.light_res * d.last.light_res / t),
                        .e_tot = std::hypot(e_disc, e_comp),
                        .e_tot_default = std::hypot(e_disc, e_comp),
                        .seconds = 1});
    } else {
      break;
    }
  }
  return d;
}

TEST(AutoSearchTest, ColumnTargetIsTheSafetyShareOfWhatDiscretizationLeaves) {
  AutoSearchConfig c;
  c.target_error = 0.05;
  c.safety = 0.8;
  // sqrt(0.05² − 0.03²) = 0.04 (a 3-4-5 triangle).
  EXPECT_NEAR(*ColumnTargetFor(c, 0.03), 0.032, 1e-12);
  EXPECT_NEAR(*ColumnTargetFor(c, 0.0), 0.04, 1e-12);
  EXPECT_FALSE(ColumnTargetFor(c, 0.048).has_value()) << "0.048 > 0.95 · 0.05: no room";
  c.min_column_target = 0.02;
  EXPECT_EQ(*ColumnTargetFor(c, 0.0475), 0.02) << "clamped to the floor";
}

TEST(AutoSearchTest, TighteningScalesTheOvershootOfTheCompressionError) {
  AutoSearchConfig c;
  c.target_error = 0.05;
  c.safety = 1;
  // e_disc 0.03 leaves e_comp 0.04; a measured e_comp of 0.08 is twice
  // that budget → half the target.
  const double e_tot = std::hypot(0.03, 0.08);
  EXPECT_NEAR(*TightenedColumnTarget(c, 0.03, 0.04, e_tot), 0.02, 1e-12);
  // A barely-missed target still shrinks by at least 0.7×.
  EXPECT_NEAR(*TightenedColumnTarget(c, 0.03, 0.04, 0.0501), 0.028, 1e-12);
  c.min_column_target = 0.03;
  EXPECT_FALSE(TightenedColumnTarget(c, 0.03, 0.04, e_tot).has_value());
}

TEST(AutoSearchTest, StopsAtTheFirstResolutionThatMeetsTheTarget) {
  AutoSearchConfig c;
  c.target_error = 0.04;
  const Driven d = Drive(c, Model{});
  ASSERT_EQ(d.last.step, AutoStep::kDone);
  // e_disc(8) = 0.05 > 0.95·0.04: skipped unbaked; e_disc(16) = 0.025 leaves room.
  const AutoCandidate& chosen = d.search.candidates()[*d.search.chosen()];
  EXPECT_EQ(chosen.light_res, 16);
  EXPECT_LE(chosen.bake.e_tot, c.target_error);
  EXPECT_EQ(d.disc_measurements, 2) << "N = 32 is never traced";
  EXPECT_FALSE(d.search.candidates()[0].baked);
  // e_comp came out at half its budget: one more bake with twice the target,
  // which still meets E in a smaller store.
  EXPECT_EQ(d.bakes, 2);
  ASSERT_EQ(d.search.candidates().size(), 3u);
  const AutoCandidate& first = d.search.candidates()[1];
  EXPECT_TRUE(first.meets);
  EXPECT_NEAR(chosen.column_target, 2 * first.column_target, 1e-12);
  EXPECT_LT(chosen.bake.bytes, first.bake.bytes);
}

TEST(AutoSearchTest, KeepsTheFirstStoreWhenTheLoosenedBakeMisses) {
  AutoSearchConfig c;
  c.target_error = 0.04;
  const Driven d = Drive(c, Model{.a = 0.4, .k = 0.5, .cliff = 0.03});
  ASSERT_EQ(d.last.step, AutoStep::kDone);
  EXPECT_EQ(d.bakes, 2);
  const auto& cands = d.search.candidates();
  EXPECT_EQ(*d.search.chosen(), 1u) << "the first bake at N = 16";
  EXPECT_FALSE(cands.back().meets);
  EXPECT_GT(cands.back().column_target, cands[1].column_target);
}

TEST(AutoSearchTest, LooseningGrowsTheTargetByTheUnusedBudgetWithinBounds) {
  AutoSearchConfig c;
  c.target_error = 0.05;
  c.safety = 1;
  // Budget 0.04 at e_disc 0.03; a measured e_comp of 0.02 allows twice the target.
  EXPECT_NEAR(*LoosenedColumnTarget(c, 0.03, 0.01, std::hypot(0.03, 0.02)), 0.02, 1e-12);
  EXPECT_NEAR(*LoosenedColumnTarget(c, 0.03, 0.01, 0.03), 0.04, 1e-12) << "capped at 4×";
  EXPECT_FALSE(LoosenedColumnTarget(c, 0.03, 0.01, std::hypot(0.03, 0.035)).has_value())
      << "less than 1.5× is not worth a bake";
}

TEST(AutoSearchTest, RetriesOnceWithATighterTargetWhenCompressionOvershoots) {
  AutoSearchConfig c;
  c.target_error = 0.04;
  const Driven d = Drive(c, Model{.a = 0.4, .k = 2.0});  // e_comp = 2 × target
  ASSERT_EQ(d.last.step, AutoStep::kDone);
  const auto& cands = d.search.candidates();
  const AutoCandidate& chosen = cands[*d.search.chosen()];
  EXPECT_EQ(chosen.light_res, 16);
  EXPECT_EQ(d.bakes, 2);
  ASSERT_GE(cands.size(), 2u);
  EXPECT_FALSE(cands[cands.size() - 2].meets);
  EXPECT_LT(chosen.column_target, cands[cands.size() - 2].column_target);
}

TEST(AutoSearchTest, MovesToTheNextResolutionAfterAFailedRetry) {
  AutoSearchConfig c;
  c.target_error = 0.04;
  const Driven d = Drive(c, Model{.a = 0.4, .k = 0.5, .stubborn_res = 16});
  ASSERT_EQ(d.last.step, AutoStep::kDone);
  EXPECT_EQ(d.bakes, 4) << "two at N = 16, the first and a loosened one at N = 32";
  EXPECT_EQ(d.search.candidates()[*d.search.chosen()].light_res, 32);
  EXPECT_LE(d.search.candidates()[*d.search.chosen()].bake.e_tot, c.target_error);
}

TEST(AutoSearchTest, FailsNamingTheClosestCandidateWhenNoResolutionMeetsTheTarget) {
  AutoSearchConfig c;
  c.target_error = 0.01;
  c.resolutions = {8, 16, 32};
  const Driven d = Drive(c, Model{.a = 1.0});  // e_disc(32) = 0.031 > E
  ASSERT_EQ(d.last.step, AutoStep::kFailed);
  EXPECT_FALSE(d.search.chosen().has_value());
  EXPECT_EQ(d.bakes, 0) << "no resolution left room for compression";
  EXPECT_THAT(d.last.reason, HasSubstr("up to 32"));
  EXPECT_THAT(d.last.reason, HasSubstr("0.01"));
  EXPECT_THAT(d.last.reason, HasSubstr("N=32"));
}

TEST(AutoSearchTest, ALooserTargetNeverChoosesAFinerResolutionOrABiggerStore) {
  int last_n = 1 << 30;
  int64_t last_bytes = INT64_MAX;
  double last_target = 0;
  for (double e : {0.006, 0.01, 0.02, 0.04, 0.08, 0.16}) {
    AutoSearchConfig c;
    c.target_error = e;
    const Driven d = Drive(c, Model{.a = 0.05, .k = 0.5});
    ASSERT_EQ(d.last.step, AutoStep::kDone) << "E = " << e;
    const AutoCandidate& chosen = d.search.candidates()[*d.search.chosen()];
    EXPECT_LE(chosen.light_res, last_n) << "E = " << e;
    EXPECT_LE(chosen.bake.bytes, last_bytes) << "E = " << e;
    if (chosen.light_res == last_n) {
      EXPECT_GE(chosen.column_target, last_target);
    }
    last_n = chosen.light_res;
    last_bytes = chosen.bake.bytes;
    last_target = chosen.column_target;
  }
  EXPECT_EQ(last_n, 8) << "a loose target needs only the coarsest cubemap";
}

}  // namespace
}  // namespace wavebake
