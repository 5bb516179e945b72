// JobStore over SQLite (WAL): a coordinator that dies and restarts on the same
// file resumes every unfinished job (DESIGN.md §4).
#include "coordinator/state/job_store.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <string>

#include "coordinator/scheduling/lease_table.h"
#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// One "coordinator process": a store and its table on one file.
struct Process {
  Process(const std::string& path, FakeClock* clock, std::vector<int64_t>* cleaned = nullptr) {
    auto s = JobStore::Open(path);
    EXPECT_TRUE(s.ok()) << s.status();
    store = std::move(*s);
    auto t =
        LeaseTable::Create(store.get(), clock, {.lease_ms = 1000}, [cleaned](const JobRecord& j) {
          if (cleaned) cleaned->push_back(j.id);
        });
    EXPECT_TRUE(t.ok()) << t.status();
    table = std::move(*t);
  }
  LeaseGrant Lease(int64_t worker) {
    auto g = table->Lease(worker);
    EXPECT_TRUE(g.ok() && g->has_value());
    return g.ok() && g->has_value() ? **g : LeaseGrant{};
  }
  std::unique_ptr<JobStore> store;
  std::unique_ptr<LeaseTable> table;  // destroyed first
};

class JobStoreTest : public ::testing::Test {
 protected:
  std::string DbPath() const { return (dir_.path() / "state.sqlite").string(); }
  testing::TempDir dir_;
  FakeClock clock_;
};

TEST_F(JobStoreTest, RestartResumesJobWithLeasedTasksPending) {
  int64_t job = 0, worker = 0;
  {
    Process p(DbPath(), &clock_);
    job = p.table->ReserveJobId();
    ASSERT_TRUE(p.table
                    ->AddJob(job, testing::Serialized(testing::BuiltinRequest()), 3,
                             testing::Plan(4, 1, "resume.wbk"))
                    .ok());
    worker = *p.table->RegisterWorker("w", 2);
    const LeaseGrant t0 = p.Lease(worker);
    p.Lease(worker);
    p.Lease(worker);
    ASSERT_TRUE(*p.table->Complete(worker, t0.key, {.rays_traced = 500}));
    EXPECT_EQ(p.table->Get(job)->leased_tasks, 2);
  }  // the coordinator "dies" with tiles 1 and 2 leased

  Process p(DbPath(), &clock_);
  auto tasks = p.store->ReadTasks(job);
  ASSERT_TRUE(tasks.ok());
  ASSERT_EQ(tasks->size(), 7u);  // 4 tiles, 1 group, FINALIZE's shard and last task
  EXPECT_EQ((*tasks)[0].state, TaskState::kDone);
  EXPECT_EQ((*tasks)[0].rays_traced, 500);
  EXPECT_EQ((*tasks)[1].state, TaskState::kPending);
  EXPECT_EQ((*tasks)[1].attempts, 1);
  EXPECT_EQ((*tasks)[1].failures, 0);  // a restart is nobody's failure
  EXPECT_EQ((*tasks)[2].state, TaskState::kPending);

  auto info = p.table->Get(job);
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->record.phase, Phase::kBaking);
  EXPECT_EQ(info->tasks_done, 1);
  EXPECT_EQ(info->leased_tasks, 0);
  EXPECT_EQ(info->rays_traced, 500);
  EXPECT_EQ(info->record.store_path, "resume.wbk");

  // The worker is still registered; leased tiles come back, the done one does not.
  std::vector<int> order;
  for (int i = 0; i < 3; ++i) order.push_back(p.Lease(worker).kind_index);
  EXPECT_THAT(order, ElementsAre(1, 2, 3));
  EXPECT_GT(p.table->ReserveJobId(), job);  // ids are never reused

  auto events = p.store->ReadEvents(job, 0, 1000);
  ASSERT_TRUE(events.ok());
  bool resumed = false;
  for (size_t i = 0; i < events->size(); ++i) {
    EXPECT_EQ((*events)[i].seq, static_cast<int64_t>(i + 1));  // gap-free across the restart
    resumed |= (*events)[i].kind == EventKind::kResumed;
  }
  EXPECT_TRUE(resumed);
}

TEST_F(JobStoreTest, RestartInTransformStageKeepsStage) {
  int64_t job = 0, worker = 0;
  {
    Process p(DbPath(), &clock_);
    job = p.table->ReserveJobId();
    ASSERT_TRUE(p.table->AddJob(job, "", 3, testing::Plan(2, 2)).ok());
    worker = *p.table->RegisterWorker("w", 1);
    for (int i = 0; i < 2; ++i) ASSERT_TRUE(*p.table->Complete(worker, p.Lease(worker).key, {}));
    EXPECT_EQ(p.Lease(worker).kind, TaskKind::kTransformColumns);
  }
  Process p(DbPath(), &clock_);
  EXPECT_EQ(p.table->Get(job)->record.phase, Phase::kTransforming);
  const LeaseGrant g = p.Lease(worker);
  EXPECT_EQ(g.kind, TaskKind::kTransformColumns);
  EXPECT_EQ(g.kind_index, 0);
  EXPECT_EQ(g.key.attempt, 2);
}

// FINALIZE's last task waits for every shard across a restart too: with one
// shard done and one leased when the coordinator dies, the resumed job
// leases the shard again first and the last task only after it.
TEST_F(JobStoreTest, RestartInFinalizeStageHoldsTheLastTaskForItsShards) {
  int64_t job = 0, worker = 0;
  {
    Process p(DbPath(), &clock_);
    job = p.table->ReserveJobId();
    ASSERT_TRUE(p.table->AddJob(job, "", 3, testing::Plan(1, 2)).ok());
    worker = *p.table->RegisterWorker("w", 1);
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(*p.table->Complete(worker, p.Lease(worker).key, {}));
    const LeaseGrant s0 = p.Lease(worker), s1 = p.Lease(worker);
    ASSERT_EQ(s0.kind, TaskKind::kFinalize);
    ASSERT_EQ(s1.kind_index, 1);
    ASSERT_TRUE(*p.table->Complete(worker, s0.key, {}));
  }  // dies with shard 1 leased
  Process p(DbPath(), &clock_);
  EXPECT_EQ(p.table->Get(job)->record.phase, Phase::kFinalizing);
  const LeaseGrant again = p.Lease(worker);
  EXPECT_EQ(again.kind_index, 1);
  EXPECT_FALSE(p.table->Lease(worker)->has_value());  // the last task waits for shard 1
  ASSERT_TRUE(*p.table->Complete(worker, again.key, {}));
  const LeaseGrant last = p.Lease(worker);
  EXPECT_EQ(last.kind, TaskKind::kFinalize);
  EXPECT_EQ(last.kind_index, 2);
  ASSERT_TRUE(*p.table->Complete(worker, last.key, {.stats_json = R"({"nnz":1})"}));
  EXPECT_EQ(p.table->Get(job)->record.phase, Phase::kDone);
  EXPECT_EQ(p.table->Get(job)->record.stats_json, R"({"nnz":1})");
}

// A job planned by a coordinator from before FINALIZE was split (one
// FINALIZE row, leased when it died) resumes under the split layout: its
// row becomes shard 0, the other shard and the last task are added, and the
// job finishes, instead of the coordinator refusing to start.
TEST_F(JobStoreTest, JobWithTheOneTaskFinalizeLayoutResumesWithShards) {
  int64_t job = 0, worker = 0;
  {
    Process p(DbPath(), &clock_);
    job = p.table->ReserveJobId();
    ASSERT_TRUE(p.table->AddJob(job, "", 3, testing::Plan(1, 2)).ok());
    worker = *p.table->RegisterWorker("w", 1);
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(*p.table->Complete(worker, p.Lease(worker).key, {}));
    const LeaseGrant shard0 = p.Lease(worker);
    ASSERT_EQ(shard0.kind, TaskKind::kFinalize);
  }  // dies with FINALIZE leased
  {  // the rows as the one-task layout had them: tiles, groups, one FINALIZE
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(DbPath().c_str(), &db), SQLITE_OK);
    const std::string sql = "DELETE FROM tasks WHERE job_id = " + std::to_string(job) +
                            " AND idx > 3; UPDATE tasks SET kind_index = 0 WHERE idx = 3";
    EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
  }
  Process p(DbPath(), &clock_);
  ASSERT_EQ(p.table->Get(job)->record.phase, Phase::kFinalizing);
  EXPECT_EQ(p.store->ReadTasks(job)->size(), 6u);  // 1 tile, 2 groups, 2 shards, the last
  const LeaseGrant a = p.Lease(worker), b = p.Lease(worker);
  EXPECT_EQ(a.kind_index + b.kind_index, 1);          // shards 0 and 1
  EXPECT_FALSE(p.table->Lease(worker)->has_value());  // the last task waits for both
  ASSERT_TRUE(*p.table->Complete(worker, a.key, {}));
  ASSERT_TRUE(*p.table->Complete(worker, b.key, {}));
  const LeaseGrant last = p.Lease(worker);
  EXPECT_EQ(last.kind_index, 2);
  ASSERT_TRUE(*p.table->Complete(worker, last.key, {}));
  EXPECT_EQ(p.table->Get(job)->record.phase, Phase::kDone);
}

TEST_F(JobStoreTest, CleanupInterruptedByRestartRunsAtStart) {
  std::vector<int64_t> cleaned;
  int64_t job = 0;
  {
    Process p(DbPath(), &clock_, &cleaned);
    job = p.table->ReserveJobId();
    ASSERT_TRUE(p.table->AddJob(job, "", 3, testing::Plan(2, 1)).ok());
    const int64_t w = *p.table->RegisterWorker("w", 1);
    p.Lease(w);
    ASSERT_TRUE(p.table->Cancel(job).ok());
    EXPECT_TRUE(cleaned.empty());  // waits for the outstanding lease
  }
  Process p(DbPath(), &clock_, &cleaned);  // the old leases are void now
  EXPECT_THAT(cleaned, ElementsAre(job));
  EXPECT_EQ(p.table->Get(job)->record.phase, Phase::kCancelled);
  Process again(DbPath(), &clock_, &cleaned);
  EXPECT_THAT(cleaned, ElementsAre(job));  // once only
}

TEST_F(JobStoreTest, ExcludedWorkerStaysExcluded) {
  int64_t w = 0;
  {
    Process p(DbPath(), &clock_);
    const int64_t job = p.table->ReserveJobId();
    ASSERT_TRUE(p.table->AddJob(job, "", 50, testing::Plan(5, 1)).ok());
    w = *p.table->RegisterWorker("flaky", 1);
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(*p.table->Fail(w, p.Lease(w).key, "boom"));
  }
  Process p(DbPath(), &clock_);
  EXPECT_EQ(p.table->Lease(w).status().code(), absl::StatusCode::kFailedPrecondition);
}

TEST_F(JobStoreTest, ScenesAreKeyedByHash) {
  auto store = JobStore::Open(DbPath());
  ASSERT_TRUE(store.ok());
  SceneRecord a{.sha256 = std::string(64, 'a'), .size = 10, .file_name = "a.obj", .created_ms = 1};
  ASSERT_TRUE((*store)->PutScene(a).ok());
  SceneRecord again = a;
  again.file_name = "renamed.obj";
  ASSERT_TRUE((*store)->PutScene(again).ok());
  auto found = (*store)->GetScene(a.sha256);
  ASSERT_TRUE(found.ok() && found->has_value());
  EXPECT_EQ((*found)->file_name, "a.obj");  // first upload's name is kept
  EXPECT_EQ((*found)->size, 10);
  EXPECT_FALSE((*store)->GetScene(std::string(64, 'b'))->has_value());
}

TEST_F(JobStoreTest, UsesWalJournal) {
  auto store = JobStore::Open(DbPath());
  ASSERT_TRUE(store.ok());
  EXPECT_TRUE(std::filesystem::exists(DbPath() + "-wal"));
}

TEST_F(JobStoreTest, UnopenablePathIsAnError) {
  auto store = JobStore::Open((dir_.path() / "missing" / "dir" / "x.sqlite").string());
  EXPECT_FALSE(store.ok());
  EXPECT_THAT(store.status().message(), HasSubstr("open"));
}

}  // namespace
}  // namespace wavebake
