// The job's ETA (coordinator/scheduling/eta_model.h): from measured task times of the
// running stage, priors scaled by the tile stage's wall time for stages not
// begun, 0 once the job is done. Expected values follow the model's
// definition by hand, with a fake clock so task times are exact.
#include <gtest/gtest.h>

#include "coordinator/scheduling/eta_model.h"
#include "coordinator/scheduling/lease_table.h"
#include "coordinator/service/proto_convert.h"
#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

TEST(EtaModelTest, RunningStageFromMeasuredTaskTimes) {
  EtaInputs in;
  in.current = 1;  // the column stage
  in.parallelism = 2;
  in.tile_stage_seconds = 10;
  in.stages[0].tasks = in.stages[0].done = 4;
  // 6 groups: 2 done at 3 s each, 1 running for 1 s, 3 pending.
  in.stages[1] = {.tasks = 6, .done = 2, .measured = 2, .measured_seconds = 6, .running = {1.0}};
  in.stages[2].tasks = 1;
  // (3 pending × 3 s + (3 − 1) s) / 2 workers + FINALIZE's prior 0.3 × 10 s
  EXPECT_DOUBLE_EQ(EstimateEta(in), (3 * 3.0 + 2.0) / 2 + kFinalizeRatio * 10);
}

TEST(EtaModelTest, OneLongTaskIsNotSpreadOverIdleWorkers) {
  EtaInputs in;
  in.current = 1;
  in.parallelism = 8;
  in.tile_stage_seconds = 10;
  in.stages[1] = {.tasks = 3, .done = 2, .measured = 2, .measured_seconds = 8, .running = {1.0}};
  EXPECT_DOUBLE_EQ(EstimateEta(in), 3.0 + kFinalizeRatio * 10);  // 4 s task, 1 s in
}

TEST(EtaModelTest, UnmeasuredStageTakesAtLeastItsOldestTask) {
  EtaInputs in;
  in.current = 1;
  in.parallelism = 2;
  in.tile_stage_seconds = 4;  // column prior: 0.25 × 4 s over 2 groups on 2 workers = 1 s each
  in.stages[1] = {.tasks = 2, .running = {5.0, 5.0}};
  EXPECT_DOUBLE_EQ(EstimateEta(in), kFinalizeRatio * 4);  // both past the prior: only FINALIZE
  in.stages[1].running = {0.25, 0.25};
  EXPECT_DOUBLE_EQ(EstimateEta(in), 0.75 + kFinalizeRatio * 4);
}

TEST(EtaModelTest, TileStageFromRaysBeforeAnyTileIsDone) {
  EtaInputs in;
  in.current = 0;
  in.stage_elapsed = 3;
  in.tile_rays_fraction = 0.25;  // 3 s for a quarter: 9 s to go, B = 12 s
  in.stages[0] = {.tasks = 4, .running = {3.0}};
  EXPECT_DOUBLE_EQ(EstimateEta(in), 9 + (kColumnStageRatio + kFinalizeRatio) * 12);
  in.tile_rays_fraction = -1;
  in.stages[0].running.clear();
  EXPECT_EQ(EstimateEta(in), -1);  // nothing leased, nothing traced: unknown
}

// A job through its stages on a fake clock; two workers.
TEST(LeaseTableEtaTest, FollowsTheStagesAndEndsAtZero) {
  FakeClock clock;
  auto table = *LeaseTable::Create(nullptr, &clock, {.lease_ms = 60'000}, nullptr);
  const int64_t job = table->ReserveJobId();
  ASSERT_TRUE(
      table->AddJob(job, testing::Serialized(testing::BuiltinRequest()), 3, testing::Plan(4, 4))
          .ok());
  const int64_t w1 = *table->RegisterWorker("a", 1), w2 = *table->RegisterWorker("b", 1);
  auto lease = [&](int64_t w) { return (**table->Lease(w)).key; };
  auto done = [&](const LeaseKey& k, int64_t w) {
    ASSERT_TRUE(*table->Complete(w, k, {.rays_traced = 1000}));
  };
  auto eta = [&] { return table->Get(job)->eta_seconds; };

  LeaseKey a = lease(w1), b = lease(w2);  // tiles 0, 1 at t = 0
  clock.Advance(1000);
  done(a, w1), done(b, w2);      // 1 s each
  a = lease(w1), b = lease(w2);  // tiles 2, 3
  clock.Advance(500);
  // Tiles: 0.5 s left on both; B = 1.5 + 0.5 = 2 s; then the priors.
  EXPECT_DOUBLE_EQ(eta(), 0.5 + (kColumnStageRatio + kFinalizeRatio) * 2);
  clock.Advance(500);
  done(a, w1), done(b, w2);
  ASSERT_EQ(table->Get(job)->record.phase, Phase::kTransforming);

  a = lease(w1), b = lease(w2);  // groups 0, 1 at t = 2 s
  clock.Advance(3000);
  // No group done; both have run 3 s, far past the prior: 2 more groups of
  // at least 3 s on 2 workers, then FINALIZE.
  EXPECT_DOUBLE_EQ(eta(), 3 + kFinalizeRatio * 2);
  done(a, w1), done(b, w2);  // measured: 3 s each
  a = lease(w1), b = lease(w2);
  clock.Advance(1000);
  EXPECT_DOUBLE_EQ(eta(), 2 + kFinalizeRatio * 2);  // 2 s left on each running group
  clock.Advance(2000);
  done(a, w1), done(b, w2);
  ASSERT_EQ(table->Get(job)->record.phase, Phase::kFinalizing);

  a = lease(w1);
  clock.Advance(100);
  EXPECT_NEAR(eta(), kFinalizeRatio * 2 - 0.1, 1e-12);
  clock.Advance(100);
  done(a, w1);
  // FINALIZE's other three shards and its last task (core/finalize_shards.h).
  for (int i = 0; i < 4; ++i) done(lease(w1), w1);
  EXPECT_EQ(table->Get(job)->record.phase, Phase::kDone);
  EXPECT_EQ(eta(), 0);
}

// Persisted events carry no estimate, except that a DONE job has none left.
TEST(LeaseTableEtaTest, TheDonePhaseEventSaysZero) {
  JobRecord job{.id = 1, .tiles = 1, .groups = 1};
  v1::JobEvent out;
  ToProto(EventRecord{.job_id = 1, .seq = 9, .kind = EventKind::kPhase, .phase = Phase::kDone}, job,
          &out);
  EXPECT_EQ(out.eta_seconds(), 0);
  ToProto(EventRecord{.job_id = 1, .seq = 3, .kind = EventKind::kPhase, .phase = Phase::kBaking},
          job, &out);
  EXPECT_EQ(out.eta_seconds(), -1);
}

}  // namespace
}  // namespace wavebake
