// LeaseTable with a fake clock and no database: stages, ordering, expiry,
// attempts, worker exclusion, cancel and cleanup (DESIGN.md §2, §4).
#include "coordinator/scheduling/lease_table.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

class LeaseTableTest : public ::testing::Test {
 protected:
  void SetUp() override { table_ = MakeTable(); }

  std::unique_ptr<LeaseTable> MakeTable(int failure_limit = 3) {
    auto table = LeaseTable::Create(nullptr, &clock_,
                                    {.lease_ms = 1000, .worker_failure_limit = failure_limit},
                                    [this](const JobRecord& j) { cleaned_.push_back(j.id); });
    EXPECT_TRUE(table.ok()) << table.status();
    return std::move(*table);
  }

  int64_t AddJob(int tiles, int groups, int max_attempts = 3, std::string store = "") {
    const int64_t id = table_->ReserveJobId();
    if (store.empty()) store = "job" + std::to_string(id) + ".wbk";
    auto info = table_->AddJob(id, testing::Serialized(testing::BuiltinRequest()), max_attempts,
                               testing::Plan(tiles, groups, store));
    EXPECT_TRUE(info.ok()) << info.status();
    return id;
  }

  int64_t Worker() { return *table_->RegisterWorker("w", 1); }

  // The next grant for `worker`, as "KIND index" ("-" when told to wait).
  std::string Next(int64_t worker, LeaseGrant* grant = nullptr) {
    auto g = table_->Lease(worker);
    EXPECT_TRUE(g.ok()) << g.status();
    if (!g.ok() || !g->has_value()) return "-";
    if (grant) *grant = **g;
    return std::string(TaskKindName((*g)->kind)) + " " + std::to_string((*g)->kind_index);
  }

  bool Done(int64_t worker, const LeaseGrant& g, std::string stats = "{}") {
    auto ok = table_->Complete(worker, g.key,
                               {.rays_traced = 1000, .bytes_written = 10, .stats_json = stats});
    EXPECT_TRUE(ok.ok()) << ok.status();
    return ok.ok() && *ok;
  }

  Phase PhaseOf(int64_t job) { return table_->Get(job)->record.phase; }

  FakeClock clock_;
  std::vector<int64_t> cleaned_;
  std::unique_ptr<LeaseTable> table_;
};

TEST_F(LeaseTableTest, TilesThenGroupsThenFinalize) {
  const int64_t job = AddJob(2, 2);
  const int64_t w = Worker();
  EXPECT_EQ(PhaseOf(job), Phase::kQueued);
  LeaseGrant t0, t1, g0, g1, fin;
  EXPECT_EQ(Next(w, &t0), "BAKE_TILE 0");
  EXPECT_EQ(PhaseOf(job), Phase::kBaking);
  EXPECT_EQ(Next(w, &t1), "BAKE_TILE 1");
  EXPECT_EQ(Next(w), "-");                               // groups wait for every tile (§2)
  EXPECT_EQ(table_->Get(job)->rays_estimate, 2 * 1000);  // the planner's, no tile done
  clock_.Advance(500);
  EXPECT_TRUE(Done(w, t1));
  auto mid = table_->Get(job);
  EXPECT_DOUBLE_EQ(mid->rays_per_second, 2000);  // 1000 rays in 0.5 s
  EXPECT_GT(mid->eta_seconds, 0);
  EXPECT_EQ(Next(w), "-");  // tile 0 still out
  EXPECT_TRUE(Done(w, t0));
  EXPECT_EQ(PhaseOf(job), Phase::kTransforming);
  EXPECT_EQ(Next(w, &g0), "TRANSFORM_COLUMNS 0");
  EXPECT_EQ(Next(w, &g1), "TRANSFORM_COLUMNS 1");
  EXPECT_EQ(Next(w), "-");
  EXPECT_TRUE(Done(w, g0));
  EXPECT_TRUE(Done(w, g1));
  EXPECT_EQ(PhaseOf(job), Phase::kFinalizing);
  // FINALIZE: one shard per group, then its last task once both are done.
  LeaseGrant s0, s1;
  EXPECT_EQ(Next(w, &s0), "FINALIZE 0");
  EXPECT_EQ(Next(w, &s1), "FINALIZE 1");
  EXPECT_EQ(Next(w), "-");
  EXPECT_TRUE(Done(w, s1));
  EXPECT_EQ(Next(w), "-");  // shard 0 still out
  EXPECT_TRUE(Done(w, s0));
  EXPECT_EQ(Next(w, &fin), "FINALIZE 2");
  EXPECT_EQ(fin.tiles, 2);
  EXPECT_EQ(fin.groups, 2);
  EXPECT_TRUE(Done(w, fin, R"({"rel_rms":0.01})"));
  auto info = table_->Get(job);
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->record.phase, Phase::kDone);
  EXPECT_EQ(info->tasks_done, 7);
  EXPECT_EQ(info->rays_traced, 7000);
  EXPECT_EQ(info->record.stats_json, R"({"rel_rms":0.01})");
  EXPECT_EQ(info->eta_seconds, 0);
  EXPECT_EQ(Next(w), "-");
  EXPECT_TRUE(cleaned_.empty());  // a DONE job keeps its store
}

// The planner's bound until a tile is done; then the done tiles' rays
// extrapolated over every tile; then, every tile done, what they traced.
TEST_F(LeaseTableTest, RayEstimateFollowsTheDoneTiles) {
  const int64_t job = AddJob(4, 1);  // the planner says 4 × 1000
  const int64_t w = Worker();
  LeaseGrant t[4];
  for (int i = 0; i < 4; ++i) ASSERT_EQ(Next(w, &t[i]), "BAKE_TILE " + std::to_string(i));
  EXPECT_EQ(table_->Get(job)->rays_estimate, 4000);
  ASSERT_TRUE(*table_->Complete(w, t[0].key, {.rays_traced = 100}));
  EXPECT_EQ(table_->Get(job)->rays_estimate, 400);
  ASSERT_TRUE(*table_->Complete(w, t[1].key, {.rays_traced = 300}));
  EXPECT_EQ(table_->Get(job)->rays_estimate, 800);
  ASSERT_TRUE(*table_->Complete(w, t[2].key, {.rays_traced = 50}));
  ASSERT_TRUE(*table_->Complete(w, t[3].key, {.rays_traced = 50}));
  EXPECT_EQ(PhaseOf(job), Phase::kTransforming);
  EXPECT_EQ(table_->Get(job)->rays_estimate, 500);
}

TEST_F(LeaseTableTest, OldestJobWithReadyTaskFirst) {
  const int64_t a = AddJob(1, 1);
  const int64_t b = AddJob(2, 1);
  const int64_t w = Worker();
  LeaseGrant ta, tb;
  EXPECT_EQ(Next(w, &ta), "BAKE_TILE 0");
  EXPECT_EQ(ta.key.job_id, a);
  EXPECT_EQ(Next(w, &tb), "BAKE_TILE 0");  // job a has nothing ready: job b
  EXPECT_EQ(tb.key.job_id, b);
  EXPECT_TRUE(Done(w, ta));
  LeaseGrant next;
  EXPECT_EQ(Next(w, &next), "TRANSFORM_COLUMNS 0");  // a's group beats b's tile 1
  EXPECT_EQ(next.key.job_id, a);
  EXPECT_EQ(Next(w, &next), "BAKE_TILE 1");
  EXPECT_EQ(next.key.job_id, b);
}

TEST_F(LeaseTableTest, ExpiredLeaseReturnsToQueueAndHeartbeatKeepsIt) {
  const int64_t job = AddJob(2, 1);
  const int64_t w = Worker();
  LeaseGrant first, second;
  EXPECT_EQ(Next(w, &first), "BAKE_TILE 0");
  EXPECT_EQ(first.lease_id, std::to_string(job) + ".0.1");
  EXPECT_EQ(first.deadline_ms, clock_.NowMs() + 1000);
  EXPECT_EQ(Next(w, &second), "BAKE_TILE 1");

  // Tile 1 is renewed in time; tile 0 is not.
  clock_.Advance(800);
  LeaseProgressReport renew{.key = second.key, .rays_traced = 123};
  auto hb = table_->Heartbeat(w, std::span(&renew, 1));
  ASSERT_TRUE(hb.ok());
  EXPECT_THAT(hb->renewed, ElementsAre(second.key));
  EXPECT_EQ(table_->Get(job)->rays_traced, 123);
  clock_.Advance(300);
  ASSERT_TRUE(table_->ExpireLeases().ok());

  LeaseGrant again;
  EXPECT_EQ(Next(w, &again), "BAKE_TILE 0");  // requeued; tile 1 is still held
  EXPECT_EQ(again.key.attempt, 2);
  EXPECT_EQ(Next(w), "-");
  // The old lease is answered cancelled.
  LeaseProgressReport stale{.key = first.key};
  hb = table_->Heartbeat(w, std::span(&stale, 1));
  ASSERT_TRUE(hb.ok());
  EXPECT_THAT(hb->cancelled, ElementsAre(first.key));
  auto events = table_->Get(job);
  EXPECT_EQ(events->record.phase, Phase::kBaking);
}

TEST_F(LeaseTableTest, MaxAttemptsFailsJobWithReason) {
  const int64_t job = AddJob(3, 1, /*max_attempts=*/2);
  const int64_t w1 = Worker(), w2 = Worker();
  LeaseGrant g;
  EXPECT_EQ(Next(w1, &g), "BAKE_TILE 0");
  ASSERT_TRUE(*table_->Fail(w1, g.key, "out of memory"));
  EXPECT_EQ(PhaseOf(job), Phase::kBaking);
  LeaseGrant other;
  EXPECT_EQ(Next(w2, &other), "BAKE_TILE 0");  // the failed task first (lowest index)
  EXPECT_EQ(other.key.attempt, 2);
  LeaseGrant held;
  EXPECT_EQ(Next(w1, &held), "BAKE_TILE 1");
  // Expiry counts as a failure too: tile 0 has failed once, this is its second.
  clock_.Advance(1001);
  ASSERT_TRUE(table_->ExpireLeases().ok());
  auto info = table_->Get(job);
  EXPECT_EQ(info->record.phase, Phase::kFailed);
  EXPECT_THAT(info->record.error, HasSubstr("BAKE_TILE 0 failed 2 times"));
  EXPECT_THAT(info->record.error, HasSubstr("lease expired"));
  EXPECT_THAT(cleaned_, ElementsAre(job));  // both leases expired: nothing outstanding
  EXPECT_EQ(Next(w1), "-");
}

TEST_F(LeaseTableTest, FailureReasonEndsUpInJobError) {
  const int64_t job = AddJob(1, 1, /*max_attempts=*/1);
  const int64_t w = Worker();
  LeaseGrant g;
  Next(w, &g);
  ASSERT_TRUE(*table_->Fail(w, g.key, "NaN vertices in mesh 3"));
  auto info = table_->Get(job);
  EXPECT_EQ(info->record.phase, Phase::kFailed);
  EXPECT_THAT(info->record.error, HasSubstr("NaN vertices in mesh 3"));
  EXPECT_THAT(cleaned_, ElementsAre(job));
  // A second Fail of the same lease is stale.
  EXPECT_FALSE(*table_->Fail(w, g.key, "again"));
}

TEST_F(LeaseTableTest, WorkerFailingInARowIsExcluded) {
  AddJob(8, 1, /*max_attempts=*/100);
  const int64_t bad = Worker(), good = Worker();
  LeaseGrant g;
  // Two failures, a success (resets the count), then three failures.
  for (int i = 0; i < 2; ++i) {
    Next(bad, &g);
    ASSERT_TRUE(*table_->Fail(bad, g.key, "segfault"));
  }
  Next(bad, &g);
  EXPECT_TRUE(Done(bad, g));
  for (int i = 0; i < 3; ++i) {
    ASSERT_NE(Next(bad, &g), "-");
    ASSERT_TRUE(*table_->Fail(bad, g.key, "segfault"));
  }
  auto refused = table_->Lease(bad);
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(refused.status().message(), HasSubstr("excluded"));
  EXPECT_NE(Next(good), "-");
  EXPECT_EQ(table_->Lease(999).status().code(), absl::StatusCode::kNotFound);
}

// A job whose input is bad fails on every worker. Retried as transient
// failures, its many tasks would exclude each healthy worker after
// worker_failure_limit of them before any one task ran out of attempts, and
// the job would wait forever. A permanent failure ends it at once instead.
TEST_F(LeaseTableTest, APermanentFailureFailsTheJobAndSparesTheWorker) {
  const int64_t bad_job = AddJob(8, 1);
  const int64_t w = Worker();
  LeaseGrant g;
  EXPECT_EQ(Next(w, &g), "BAKE_TILE 0");
  ASSERT_TRUE(*table_->Fail(w, g.key, "scene: NaN vertex 3", LeaseTable::Failure::kPermanent));
  auto info = table_->Get(bad_job);
  EXPECT_EQ(info->record.phase, Phase::kFailed);
  EXPECT_THAT(info->record.error,
              HasSubstr("failed, not retried (its input, or a full disk): worker"));
  EXPECT_THAT(info->record.error, HasSubstr("NaN vertex 3"));
  // Twice the exclusion limit of permanent failures, and the worker still works.
  for (int i = 0; i < 6; ++i) {
    AddJob(1, 1);
    ASSERT_NE(Next(w, &g), "-");
    ASSERT_TRUE(*table_->Fail(w, g.key, "bad", LeaseTable::Failure::kPermanent));
  }
  const int64_t good_job = AddJob(1, 1);
  ASSERT_EQ(Next(w, &g), "BAKE_TILE 0");
  EXPECT_EQ(g.key.job_id, good_job);
}

TEST_F(LeaseTableTest, CancelStopsLeasesThenCleansUp) {
  const int64_t job = AddJob(3, 1);
  const int64_t w = Worker();
  LeaseGrant g;
  Next(w, &g);
  auto info = table_->Cancel(job);
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->record.phase, Phase::kCancelled);
  EXPECT_EQ(Next(w), "-");
  EXPECT_TRUE(cleaned_.empty());  // a worker may still be writing into the store

  LeaseProgressReport p{.key = g.key};
  auto hb = table_->Heartbeat(w, std::span(&p, 1));
  ASSERT_TRUE(hb.ok());
  EXPECT_THAT(hb->cancelled, ElementsAre(g.key));
  EXPECT_TRUE(hb->renewed.empty());
  EXPECT_THAT(cleaned_, ElementsAre(job));

  EXPECT_TRUE(table_->Cancel(job).ok());  // idempotent
  EXPECT_THAT(cleaned_, ElementsAre(job));
  EXPECT_FALSE(*table_->Complete(w, g.key, {}));  // ignored
  EXPECT_EQ(table_->Cancel(12345).status().code(), absl::StatusCode::kNotFound);
}

TEST_F(LeaseTableTest, CancelOfDoneJobIsRefused) {
  const int64_t job = AddJob(1, 1);
  const int64_t w = Worker();
  LeaseGrant g;
  while (Next(w, &g) != "-") Done(w, g);
  EXPECT_EQ(PhaseOf(job), Phase::kDone);
  EXPECT_EQ(table_->Cancel(job).status().code(), absl::StatusCode::kFailedPrecondition);
}

TEST_F(LeaseTableTest, LateResultOfExpiredLeaseIsAcceptedOnce) {
  const int64_t job = AddJob(2, 1);
  const int64_t w1 = Worker(), w2 = Worker();
  LeaseGrant old_lease, new_lease;
  Next(w1, &old_lease);
  clock_.Advance(1500);
  EXPECT_EQ(Next(w2, &new_lease), "BAKE_TILE 0");  // expired at this Lease call
  // w1 finishes anyway: output is deterministic (§1), so the result counts...
  EXPECT_TRUE(Done(w1, old_lease));
  // ...and w2's lease is superseded.
  LeaseProgressReport p{.key = new_lease.key};
  EXPECT_THAT(table_->Heartbeat(w2, std::span(&p, 1))->cancelled, ElementsAre(new_lease.key));
  EXPECT_FALSE(Done(w2, new_lease));  // not needed any more
  EXPECT_EQ(table_->Get(job)->tasks_done, 1);
  EXPECT_EQ(Next(w2), "BAKE_TILE 1");
  // A lease that was never granted is NOT_FOUND.
  LeaseKey bogus{job, 1, 7};
  EXPECT_EQ(table_->Complete(w1, bogus, {}).status().code(), absl::StatusCode::kNotFound);
}

TEST_F(LeaseTableTest, SameStorePathTwiceIsRefusedWhileRunning) {
  AddJob(1, 1, 3, "same.wbk");
  const int64_t id = table_->ReserveJobId();
  auto second = table_->AddJob(id, "", 3, testing::Plan(1, 1, "same.wbk"));
  EXPECT_EQ(second.status().code(), absl::StatusCode::kAlreadyExists);
  auto bad = table_->AddJob(table_->ReserveJobId(), "", 3, testing::Plan(1, 1, "../escape"));
  EXPECT_EQ(bad.status().code(), absl::StatusCode::kInternal);
  auto empty = table_->AddJob(table_->ReserveJobId(), "", 3, testing::Plan(0, 1, "x.wbk"));
  EXPECT_EQ(empty.status().code(), absl::StatusCode::kInternal);
}

TEST_F(LeaseTableTest, ListNewestFirst) {
  const int64_t a = AddJob(1, 1), b = AddJob(1, 1);
  ASSERT_TRUE(table_->Cancel(a).ok());
  auto all = table_->List(10, false);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].record.id, b);
  auto active = table_->List(10, true);
  ASSERT_EQ(active.size(), 1u);
  EXPECT_EQ(active[0].record.id, b);
}

// /metrics' snapshot: a registered worker is alive only once it leases (its
// store-root check lies between Register and the first Lease), and only
// until a lease period passes without a call; per-job numbers cover live
// jobs, finished ones only their phase count.
TEST_F(LeaseTableTest, MetricsCountCheckedWorkersAndLiveJobs) {
  const int64_t finished = AddJob(1, 1);
  const int64_t live = AddJob(2, 1);
  const int64_t w = Worker();
  Worker();  // registers, then (say) fails its store-root check and exits
  SchedulerSnapshot s = table_->Metrics(100);
  EXPECT_EQ(s.workers_registered, 2);
  EXPECT_EQ(s.workers_alive, 0);

  LeaseGrant g;
  ASSERT_EQ(Next(w, &g), "BAKE_TILE 0");
  ASSERT_TRUE(Done(w, g));
  ASSERT_EQ(Next(w, &g), "TRANSFORM_COLUMNS 0");
  ASSERT_TRUE(Done(w, g));
  ASSERT_EQ(Next(w, &g), "FINALIZE 0");
  ASSERT_TRUE(Done(w, g));
  ASSERT_EQ(Next(w, &g), "FINALIZE 1");
  ASSERT_TRUE(Done(w, g));
  ASSERT_EQ(PhaseOf(finished), Phase::kDone);
  s = table_->Metrics(100);
  EXPECT_EQ(s.workers_alive, 1);
  EXPECT_EQ(s.jobs_by_phase[static_cast<int>(Phase::kDone) - 1], 1);
  EXPECT_EQ(s.jobs_by_phase[static_cast<int>(Phase::kQueued) - 1], 1);
  ASSERT_EQ(s.jobs.size(), 1u);
  EXPECT_EQ(s.jobs[0].id, live);
  EXPECT_EQ(s.jobs[0].tasks_total, 5);  // 2 tiles, 1 group, FINALIZE's shard and last task

  clock_.Advance(1001);  // one lease period without a call
  EXPECT_EQ(table_->Metrics(100).workers_alive, 0);
}

TEST(LeaseIdTest, RoundTripAndRejects) {
  LeaseKey k{42, 7, 3};
  EXPECT_EQ(FormatLeaseId(k), "42.7.3");
  EXPECT_EQ(ParseLeaseId("42.7.3"), k);
  for (const char* bad : {"", "42", "42.7", "a.b.c", "42.7.0", "-1.2.3", "1.2.3.4"}) {
    EXPECT_FALSE(ParseLeaseId(bad).has_value()) << bad;
  }
  EXPECT_EQ(ParseId("17"), 17);
  EXPECT_FALSE(ParseId("0").has_value());
  EXPECT_FALSE(ParseId("+1").has_value());
  EXPECT_FALSE(ParseId("99999999999999999999").has_value());
}

}  // namespace
}  // namespace wavebake
