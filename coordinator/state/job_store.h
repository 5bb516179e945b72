#pragma once
// Persistent coordinator state in SQLite, WAL mode (DESIGN.md §4: "keeps jobs
// and tasks in SQLite (WAL) and resumes after a restart"). Tables: jobs,
// tasks, events, workers, scenes. The store holds no scheduling logic: the
// LeaseTable decides every transition and commits it here as one Transition
// = one SQLite transaction, so a crash never leaves half a transition.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "coordinator/scheduling/job_types.h"
#include "coordinator/state/sqlite_util.h"

namespace wavebake {

// One state transition: rows upserted and events appended atomically.
struct Transition {
  std::vector<JobRecord> jobs;
  std::vector<TaskRecord> tasks;
  std::vector<EventRecord> events;
  std::vector<WorkerRecord> workers;
};

struct StoreSnapshot {
  std::vector<JobRecord> jobs;                // every job, by id
  std::vector<TaskRecord> tasks;              // tasks of unfinished jobs, by (job, index)
  std::vector<WorkerRecord> workers;          // by id
  std::map<int64_t, int64_t> last_event_seq;  // job id -> highest event seq
};

class JobStore {
  struct Key {};  // only Open constructs a JobStore

 public:
  explicit JobStore(Key) {}
  // path: the SQLite file (created if missing), or ":memory:" for a private
  // in-memory database (tests, benchmarks).
  static absl::StatusOr<std::unique_ptr<JobStore>> Open(const std::string& path);

  absl::Status Commit(const Transition& t);
  absl::StatusOr<StoreSnapshot> Load();

  // Events of a job with seq > after_seq, in order, at most `limit`. Uses its
  // own read connection, so Watch streams do not wait for writers (WAL).
  absl::StatusOr<std::vector<EventRecord>> ReadEvents(int64_t job_id, int64_t after_seq, int limit);
  absl::StatusOr<std::vector<TaskRecord>> ReadTasks(int64_t job_id);

  // Fault injection for tests: the database may grow by at most `pages` more
  // pages (SQLite's max_page_count), after which a commit that needs one
  // fails as on a full disk (ResourceExhausted). A large value lifts it.
  absl::Status LimitGrowthForTesting(int64_t pages);
  // While set, every Commit fails as on a full disk before it writes
  // anything, however little it needs (an update in place fits any page).
  void SetFullForTesting(bool full) { full_for_testing_ = full; }

  // Content-addressed scenes: inserting a known hash is a no-op.
  absl::Status PutScene(const SceneRecord& scene);
  absl::StatusOr<std::optional<SceneRecord>> GetScene(const std::string& sha256);

 private:
  absl::Status Init(const std::string& path);
  absl::Status UpsertJob(const JobRecord& j);
  absl::Status UpsertTask(const TaskRecord& t);
  absl::Status InsertEvent(const EventRecord& e);
  absl::Status UpsertWorker(const WorkerRecord& w);
  absl::Status StartCheckpointer(const std::string& path);
  void CheckpointLoop(std::stop_token stop);
  static int OnWalCommit(void* self, sqlite3* db, const char* name, int pages);
  sqlite3* reader() { return reader_ ? reader_.get() : writer_.get(); }
  std::mutex& reader_mu() { return reader_ ? read_mu_ : write_mu_; }

  std::atomic<bool> full_for_testing_{false};
  std::mutex write_mu_;
  std::mutex read_mu_;
  SqliteDb writer_;
  SqliteDb reader_;  // null for ":memory:" (a second connection would see another database)
  SqliteStmt upsert_job_, upsert_task_, insert_event_, upsert_worker_;

  // WAL checkpoints run on their own connection and thread: a checkpoint
  // fsyncs (milliseconds on a VM disk), which would otherwise stall the
  // commit that happens to trigger it, and with it every lease.
  SqliteDb checkpointer_;
  std::mutex checkpoint_mu_;
  std::condition_variable_any checkpoint_cv_;
  bool checkpoint_due_ = false;
  std::jthread checkpoint_thread_;  // last: stopped before the connections close
};

}  // namespace wavebake
