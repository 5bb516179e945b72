// The LeaseTable on a database that runs out of space (SQLite's
// max_page_count: SQLITE_FULL, as on a full disk; or every commit refused,
// where an update in place would still fit a page) and gets it back: no job
// lives in memory without its row, a failed submit leaves no store behind, a
// FINALIZE that failed for want of space is recorded and frees its store,
// and the table recovers without a restart once space is back.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

#include "coordinator/scheduling/lease_table.h"
#include "tests/coordinator/test_util.h"

namespace wavebake {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

constexpr int64_t kPlenty = 1 << 30;  // pages: the limit lifted

class LeaseFullDiskTest : public ::testing::Test {
 protected:
  void SetUp() override { Open(); }

  void Open() {
    table_.reset();
    store_.reset();
    auto store = JobStore::Open((dir_.path() / "state.sqlite").string());
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = std::move(*store);
    auto table = LeaseTable::Create(store_.get(), &clock_, {.lease_ms = 1000},
                                    [this](const JobRecord& j) { Cleanup(j); });
    ASSERT_TRUE(table.ok()) << table.status();
    table_ = std::move(*table);
  }

  // The cleanup removes a job's store; on a full disk that is what frees
  // space, so with free_on_cleanup_ the limit goes with it.
  void Cleanup(const JobRecord& j) {
    cleaned_.push_back(j.store_path);
    if (free_on_cleanup_) Free();
  }

  void Fill() {
    ASSERT_TRUE(store_->LimitGrowthForTesting(0).ok());
    store_->SetFullForTesting(true);
  }
  void Free() {
    ASSERT_TRUE(store_->LimitGrowthForTesting(kPlenty).ok());
    store_->SetFullForTesting(false);
  }

  // 300 tiles: rows enough that the commit needs new pages.
  absl::StatusOr<JobInfo> Submit(const std::string& store) {
    return table_->AddJob(table_->ReserveJobId(), testing::Serialized(testing::BuiltinRequest()), 1,
                          testing::Plan(300, 1, store));
  }

  std::vector<int64_t> Listed() {
    std::vector<int64_t> ids;
    for (const JobInfo& j : table_->List(100, false)) ids.push_back(j.record.id);
    return ids;
  }

  testing::TempDir dir_;
  FakeClock clock_;
  std::vector<std::string> cleaned_;
  bool free_on_cleanup_ = false;
  std::unique_ptr<JobStore> store_;
  std::unique_ptr<LeaseTable> table_;
};

TEST_F(LeaseFullDiskTest, FailedSubmitLeavesNoJobAndNoStoreAndTheNextOneWorks) {
  ASSERT_TRUE(store_->LimitGrowthForTesting(0).ok());  // SQLite's own SQLITE_FULL
  absl::StatusOr<JobInfo> ghost = Submit("ghost.wbk");
  ASSERT_EQ(ghost.status().code(), absl::StatusCode::kResourceExhausted) << ghost.status();
  EXPECT_THAT(ghost.status().message(), HasSubstr("No space left on device"));
  EXPECT_THAT(Listed(), IsEmpty());                 // not QUEUED in memory without its row
  EXPECT_THAT(cleaned_, ElementsAre("ghost.wbk"));  // its reserved store goes too
  EXPECT_FALSE(table_->broken().ok());              // health: cannot record now

  Free();  // space back: no restart needed
  absl::StatusOr<JobInfo> real = Submit("real.wbk");
  ASSERT_TRUE(real.ok()) << real.status();
  EXPECT_TRUE(table_->broken().ok());
  ASSERT_TRUE(table_->Cancel(real->record.id).ok());  // cancel works again too
  Open();                                             // what the database holds: the one real job
  EXPECT_THAT(Listed(), ElementsAre(real->record.id));
  EXPECT_EQ(table_->Get(real->record.id)->record.phase, Phase::kCancelled);
}

TEST_F(LeaseFullDiskTest, FailedCancelKeepsTheJobAsTheDatabaseHasIt) {
  absl::StatusOr<JobInfo> job = Submit("a.wbk");
  ASSERT_TRUE(job.ok()) << job.status();
  const int64_t id = job->record.id;
  const int64_t w = *table_->RegisterWorker("w", 1);
  ASSERT_TRUE(table_->Lease(w).ok());  // a lease out: the store cannot go yet
  ASSERT_EQ(table_->Get(id)->record.phase, Phase::kBaking);
  Fill();
  EXPECT_EQ(table_->Cancel(id).status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(table_->Get(id)->record.phase, Phase::kBaking);  // not CANCELLED in memory alone
  EXPECT_THAT(cleaned_, IsEmpty());
  Free();
  ASSERT_TRUE(table_->ExpireLeases().ok());  // the reaper's tick recovers the table
  EXPECT_TRUE(table_->broken().ok());
  ASSERT_TRUE(table_->Cancel(id).ok());
  Open();
  EXPECT_EQ(table_->Get(id)->record.phase, Phase::kCancelled);
}

TEST_F(LeaseFullDiskTest, FinalizeFailingForSpaceIsRecordedAndFreesItsStore) {
  absl::StatusOr<JobInfo> job =
      table_->AddJob(table_->ReserveJobId(), testing::Serialized(testing::BuiltinRequest()), 1,
                     testing::Plan(1, 1, "big.wbk"));
  ASSERT_TRUE(job.ok()) << job.status();
  const int64_t id = job->record.id;
  const int64_t w = *table_->RegisterWorker("w", 1);
  for (int i = 0; i < 2; ++i) {  // the tile, then the group
    auto g = table_->Lease(w);
    ASSERT_TRUE(g.ok() && g->has_value());
    ASSERT_TRUE(*table_->Complete(w, (*g)->key, {}));
  }
  auto fin = table_->Lease(w);
  ASSERT_TRUE(fin.ok() && fin->has_value());
  ASSERT_EQ((*fin)->kind, TaskKind::kFinalize);
  // The disk is full: the store holds the space, and SQLite has none left.
  Fill();
  free_on_cleanup_ = true;
  auto counted = table_->Fail(w, (*fin)->key, "cannot write transport/data/0: No space left",
                              LeaseTable::Failure::kPermanent);
  ASSERT_TRUE(counted.ok()) << counted.status();
  EXPECT_THAT(cleaned_, ElementsAre("big.wbk"));  // removed to make room, once
  EXPECT_TRUE(table_->broken().ok());
  EXPECT_EQ(table_->Get(id)->record.phase, Phase::kFailed);
  Open();  // the database agrees, and nothing is left to clean
  EXPECT_EQ(table_->Get(id)->record.phase, Phase::kFailed);
  EXPECT_TRUE(table_->Get(id)->record.cleaned);
  EXPECT_THAT(cleaned_, ElementsAre("big.wbk"));
}

}  // namespace
}  // namespace wavebake
