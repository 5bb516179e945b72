// LeaseTable::Exchange, the transition behind WorkerService.LeaseBatch: a
// worker's results first, then its leases, as one transition; the same
// outcome as the separate Complete and Lease calls it replaces.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "coordinator/scheduling/lease_table.h"
#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

using ::testing::ElementsAre;

std::unique_ptr<LeaseTable> MakeTable(FakeClock* clock, int failure_limit = 3) {
  auto table = LeaseTable::Create(
      nullptr, clock, {.lease_ms = 1000, .worker_failure_limit = failure_limit}, nullptr);
  EXPECT_TRUE(table.ok()) << table.status();
  return std::move(*table);
}

int64_t AddJob(LeaseTable& table, int tiles, int groups) {
  const int64_t id = table.ReserveJobId();
  EXPECT_TRUE(table
                  .AddJob(id, testing::Serialized(testing::BuiltinRequest()), 3,
                          testing::Plan(tiles, groups, "job" + std::to_string(id) + ".wbk"))
                  .ok());
  return id;
}

std::vector<std::string> Names(const std::vector<LeaseGrant>& grants) {
  std::vector<std::string> out;
  for (const LeaseGrant& g : grants)
    out.push_back(std::string(TaskKindName(g.kind)) + " " + std::to_string(g.kind_index));
  return out;
}

std::vector<Completion> Results(const std::vector<LeaseGrant>& grants) {
  std::vector<Completion> out;
  for (const LeaseGrant& g : grants) out.push_back({g.key, {.rays_traced = 100}});
  return out;
}

TEST(LeaseExchangeTest, ResultsFirstThenLeasesInOneTransition) {
  FakeClock clock;
  auto table = MakeTable(&clock);
  const int64_t job = AddJob(*table, 3, 2);
  const int64_t w = *table->RegisterWorker("w", 4);
  uint64_t gen = table->generation();
  auto first = table->Exchange(w, {}, 4);
  ASSERT_TRUE(first.ok()) << first.status();
  EXPECT_THAT(Names(first->grants), ElementsAre("BAKE_TILE 0", "BAKE_TILE 1", "BAKE_TILE 2"));
  EXPECT_EQ(table->generation(), gen + 1);  // one commit for three leases
  gen = table->generation();
  // The last tile's result opens the column stage, so the same call leases groups (§2).
  auto second = table->Exchange(w, Results(first->grants), 4);
  ASSERT_TRUE(second.ok()) << second.status();
  EXPECT_THAT(second->accepted, ElementsAre(true, true, true));
  EXPECT_THAT(Names(second->grants), ElementsAre("TRANSFORM_COLUMNS 0", "TRANSFORM_COLUMNS 1"));
  EXPECT_EQ(table->generation(), gen + 1);
  EXPECT_EQ(table->Get(job)->record.rays_traced, 300);
  // FINALIZE: a shard per group, then (once both are done) its last task.
  auto third = table->Exchange(w, Results(second->grants), 4);
  EXPECT_THAT(Names(third->grants), ElementsAre("FINALIZE 0", "FINALIZE 1"));
  auto fourth = table->Exchange(w, Results(third->grants), 4);
  EXPECT_THAT(Names(fourth->grants), ElementsAre("FINALIZE 2"));
  auto last = table->Exchange(w, Results(fourth->grants), 4);
  EXPECT_TRUE(last->grants.empty());
  EXPECT_EQ(table->Get(job)->record.phase, Phase::kDone);
}

TEST(LeaseExchangeTest, AStaleOrUnknownResultIsNotAcceptedAndSpoilsNothing) {
  FakeClock clock;
  auto table = MakeTable(&clock);
  const int64_t job = AddJob(*table, 2, 1);
  const int64_t w = *table->RegisterWorker("w", 2);
  auto leased = table->Exchange(w, {}, 2);
  ASSERT_EQ(leased->grants.size(), 2u);
  std::vector<Completion> done = Results(leased->grants);
  done.insert(done.begin() + 1, {LeaseKey{job, 1, 7}, {}});  // attempt never granted
  done.push_back({LeaseKey{job, 0, 1}, {}});                 // tile 0 again: already done
  auto r = table->Exchange(w, done, 1);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_THAT(r->accepted, ElementsAre(true, false, true, false));
  EXPECT_THAT(Names(r->grants), ElementsAre("TRANSFORM_COLUMNS 0"));
  EXPECT_EQ(table->Get(job)->tasks_done, 2);
}

TEST(LeaseExchangeTest, AnExcludedWorkersResultsCountButItLeasesNothing) {
  FakeClock clock;
  auto table = MakeTable(&clock, /*failure_limit=*/1);
  const int64_t job = AddJob(*table, 3, 1);
  const int64_t w = *table->RegisterWorker("w", 2);
  auto leased = table->Exchange(w, {}, 2);
  ASSERT_EQ(leased->grants.size(), 2u);
  ASSERT_TRUE(*table->Fail(w, leased->grants[1].key, "disk full"));  // one failure: excluded
  auto r = table->Exchange(w, Results({leased->grants[0]}), 2);
  EXPECT_EQ(r.status().code(), absl::StatusCode::kFailedPrecondition) << r.status();
  EXPECT_EQ(table->Get(job)->tasks_done, 1);  // tile 0's result was taken all the same
  EXPECT_EQ(table->Get(job)->leased_tasks, 0);
}

}  // namespace
}  // namespace wavebake
