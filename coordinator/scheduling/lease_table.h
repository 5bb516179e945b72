#pragma once
// The scheduler of the coordinator (DESIGN.md §2, §4), pure logic without
// RPC: jobs, their staged tasks, the leases workers hold and their deadlines.
//
// * Lease hands out the lowest pending task of the oldest job that has one;
//   a job's TRANSFORM_COLUMNS tasks become pending only when every BAKE_TILE
//   is done, FINALIZE only when every group is done (§2).
// * A lease lasts lease_ms; Heartbeat renews it. An expired lease returns its
//   task to pending (§4). Fail calls and expiries both count as failures of
//   the task: at max_attempts failures the job FAILS with the last reason.
//   A permanent failure (the task's input is at fault) fails the job at once
//   and is not charged to the worker.
// * worker_failure_limit failures in a row (transient Fail or expiry; a
//   Complete resets the count) exclude a worker: Lease refuses it from then on.
// * Cancel ends a job at once; its outstanding leases are answered
//   "cancelled" by Heartbeat. Once none is outstanding, the cleanup callback
//   removes the partial store (FAILED jobs too), so no worker writes into a
//   directory that was just removed.
//
// Every transition is applied in memory and committed to the JobStore (if
// any) as one transaction together with its events. A new job or worker is
// published in memory only once its rows are committed. If a commit fails
// (a full disk), memory is put back as the database holds it, as a restart
// would load it: leases are void and their tasks pending again (nobody's
// failure: attempts are not charged). The table then refuses every change
// with that error, and each call (and the coordinator's reaper) tries to
// recover: reload and commit the requeue; the first that succeeds ends it,
// without a restart. A failed commit on a full disk that ends jobs (FAILED,
// CANCELLED) with no lease outstanding first removes their stores and
// commits once more, so such a job frees the space its end needs.
#include <array>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "coordinator/scheduling/clock.h"
#include "coordinator/scheduling/job_types.h"
#include "coordinator/scheduling/lease_id.h"
#include "coordinator/scheduling/scheduler_metrics.h"
#include "coordinator/state/job_store.h"

namespace wavebake {

struct LeaseTableOptions {
  int64_t lease_ms = 30'000;
  int worker_failure_limit = 3;
  int64_t max_tasks_per_job = 10'000'000;
};

// A job with its live numbers (done tasks plus what leases reported).
struct JobInfo {
  JobRecord record;
  int tasks_done = 0;
  int leased_tasks = 0;
  int64_t rays_traced = 0;
  int64_t bytes_written = 0;
  double rays_per_second = 0;
  double eta_seconds = -1;  // unknown
  // The expected total: the planner's bound (record.rays_estimate) until a
  // tile is done, then extrapolated from the done tiles (InfoLocked).
  int64_t rays_estimate = 0;
};

struct LeaseGrant {
  std::string lease_id{};
  LeaseKey key;
  TaskKind kind = TaskKind::kBakeTile;
  int kind_index = 0;  // tile or group number
  int64_t deadline_ms = 0;
  std::string request{};  // serialized v1::BakeRequest
  std::string store_path{};
  int tiles = 0, groups = 0;
};

struct LeaseProgressReport {
  LeaseKey key;
  int64_t rays_traced = 0;  // cumulative for the lease
  int64_t bytes_written = 0;
};

struct HeartbeatResult {
  std::vector<LeaseKey> renewed;
  std::vector<LeaseKey> cancelled;
  int64_t deadline_ms = 0;
};

struct TaskReport {
  int64_t rays_traced = 0;
  int64_t bytes_written = 0;
  std::string stats_json{};
};

struct Completion {
  LeaseKey key;
  TaskReport report;
};

struct ExchangeResult {
  std::vector<bool> accepted;  // per Completion, as Complete would answer
  std::vector<LeaseGrant> grants;
};

class LeaseTable {
  struct Key {};

 public:
  // store may be null: memory only (tests, benchmark baseline). Otherwise the
  // store's state is loaded and unfinished jobs resume.
  static absl::StatusOr<std::unique_ptr<LeaseTable>> Create(JobStore* store, const Clock* clock,
                                                            LeaseTableOptions options,
                                                            CleanupFn cleanup);
  LeaseTable(Key, JobStore* store, const Clock* clock, LeaseTableOptions options,
             CleanupFn cleanup);

  // Jobs. Submit = ReserveJobId (so the planner can name the store after the
  // job) + AddJob; the planner runs in between without any lock held. When
  // AddJob fails after its checks (the id was reserved, the store is no other
  // running job's), it runs the cleanup on plan.store_path: the store the
  // planner reserved goes with the job that never was.
  int64_t ReserveJobId();
  absl::StatusOr<JobInfo> AddJob(int64_t id, std::string request, int max_attempts,
                                 const PlannedJob& plan);
  absl::StatusOr<JobInfo> Get(int64_t id) const;
  std::vector<JobInfo> List(int limit, bool active_only) const;  // newest first
  absl::StatusOr<JobInfo> Cancel(int64_t id);

  // Workers.
  absl::StatusOr<int64_t> RegisterWorker(std::string name, int threads);
  absl::StatusOr<std::optional<LeaseGrant>> Lease(int64_t worker_id);  // nullopt: wait
  absl::StatusOr<HeartbeatResult> Heartbeat(int64_t worker_id,
                                            std::span<const LeaseProgressReport> leases);
  // true: accepted. A late result of an earlier lease of a task that is not
  // done yet is accepted too: task output is deterministic (§1).
  absl::StatusOr<bool> Complete(int64_t worker_id, const LeaseKey& key, const TaskReport& report);
  // A worker's report-and-lease (WorkerService.LeaseBatch): Complete each of
  // `done`, then Lease up to max_tasks, as one transition (one transaction),
  // so a worker with T idle threads pays one call and one commit, not 2T.
  // A completion of a lease that was never granted is not accepted (where
  // Complete would be NOT_FOUND). An excluded worker's completions count; its
  // leasing is FailedPrecondition, as in Lease.
  absl::StatusOr<ExchangeResult> Exchange(int64_t worker_id, std::span<const Completion> done,
                                          int max_tasks);
  // true: counted; false: the lease was stale (expired, superseded, job ended).
  enum class Failure { kTransient, kPermanent };
  absl::StatusOr<bool> Fail(int64_t worker_id, const LeaseKey& key, absl::string_view reason,
                            Failure failure = Failure::kTransient);
  // Returns expired leases to the queue; also run at every Lease/Heartbeat.
  absl::Status ExpireLeases();

  // Watch support: every change bumps the generation.
  uint64_t generation() const;
  // Waits until generation() != seen or the timeout passes; returns generation().
  uint64_t WaitForChange(uint64_t seen, int64_t timeout_ms) const;
  absl::StatusOr<std::vector<EventRecord>> ReadEvents(int64_t job_id, int64_t after_seq,
                                                      int limit) const;

  const LeaseTableOptions& options() const { return options_; }
  // The failed commit that stopped the table (a full disk under SQLite),
  // until a recovery succeeds; OK while the table works.
  absl::Status broken() const;

  // Counters, jobs by phase, workers alive (seen within lease_ms and not
  // excluded), and the task counts of the newest `job_limit` jobs.
  SchedulerSnapshot Metrics(int job_limit) const;

 private:
  struct LiveLease {
    int64_t worker_id = 0;
    int attempt = 0;
    int64_t deadline_ms = 0;
    int64_t granted_ms = 0;
    int64_t rays_traced = 0, bytes_written = 0;
  };
  // What the ETA (coordinator/scheduling/eta_model.h) knows of one stage of a job in
  // this process: when it opened and how long its done tasks took.
  struct StageClock {
    int64_t opened_ms = 0;  // 0: not in this process
    int measured = 0;
    double measured_seconds = 0;
  };
  struct JobState {
    JobRecord rec;
    std::vector<TaskRecord> tasks;  // freed once the job has ended
    std::set<int> ready;            // pending tasks of the current stage
    std::map<int, LiveLease> leases;
    int tiles_done = 0, groups_done = 0, tasks_done = 0;
    int64_t last_event_seq = 0;
    bool cleanup_scheduled = false;
    int64_t live_rays = 0, live_bytes = 0;  // sums over `leases` (kept, not recounted per event)
    std::array<StageClock, 3> stages{};     // tiles, groups, finalize
    int peak_leases = 0;
  };
  struct WorkerState {
    WorkerRecord rec;
    int64_t last_seen_ms = 0;
  };
  using Cleanups = std::vector<JobRecord>;

  absl::Status Load();
  // Memory := the store's last committed state; tx gets the resumed jobs' requeues.
  // `why` goes into the RESUMED events; the cleanups it finds due go to
  // deferred_cleanups_.
  absl::Status ReloadLocked(absl::string_view why, Transition& tx);
  // OK when not stopped; otherwise reloads, commits the requeue, and is OK
  // once that commit succeeds.
  absl::Status RecoverLocked();
  absl::Status ResumeJob(JobState& js, absl::string_view why, Transition& tx);
  // store_is_ours: set once the checks show plan.store_path is this job's alone.
  absl::StatusOr<JobInfo> AddJobLocked(int64_t id, std::string request, int max_attempts,
                                       const PlannedJob& plan, bool& store_is_ours);
  // The pending tasks of the job's stage become leasable (FINALIZE's last
  // task only once every shard is done).
  void QueueStage(JobState& js);
  void UpgradeFinalizeRows(JobState& js, Transition& tx);
  static bool ShardsDone(const JobState& js);
  // The counts (done, leased, rays, bytes); InfoLocked adds rays/s and the ETA.
  JobInfo CountsLocked(const JobState& js) const;
  JobInfo InfoLocked(const JobState& js) const;
  double EtaLocked(const JobState& js, const JobInfo& info, int64_t now_ms) const;
  void OpenStage(JobState& js, Phase phase, Transition& tx);
  void AdvanceStage(JobState& js, Transition& tx);
  void EndJob(JobState& js, Phase phase, std::string error, Transition& tx);
  void AddEvent(JobState& js, Transition& tx, EventKind kind, const TaskRecord* task = nullptr,
                std::string message = {}, int64_t worker_id = 0);
  void DropLease(JobState& js, int task);
  void MaybeCleanup(JobState& js, Cleanups& cleanups);
  void ChargeWorker(int64_t worker_id, JobState& js, Transition& tx);
  void ChargeTask(JobState& js, int task, EventKind kind, std::string reason, int64_t worker_id,
                  Transition& tx, bool permanent = false);
  void ExpireLocked(int64_t now, Transition& tx, Cleanups& cleanups);
  std::optional<LeaseGrant> LeaseOneLocked(int64_t worker_id, int64_t now, Transition& tx);
  absl::Status RefusedLocked(const WorkerState& w) const;  // OK unless excluded
  // Complete's transition into tx; NotFound for a lease never granted.
  absl::StatusOr<bool> CompleteLocked(int64_t worker_id, const LeaseKey& key,
                                      const TaskReport& report, Transition& tx, Cleanups& cleanups);
  // On failure the table is stopped and memory reloaded: no JobState& the
  // caller holds is valid any more.
  absl::Status CommitLocked(Transition& tx);
  // Runs the cleanup of the jobs tx ends (FAILED, CANCELLED) with no lease
  // left, marking them cleaned in tx; true if it removed any.
  bool FreeEndedStoresLocked(Transition& tx);
  // Also runs deferred_cleanups_.
  void RunCleanups(Cleanups cleanups);

  JobStore* const store_;
  const Clock* const clock_;
  const LeaseTableOptions options_;
  const CleanupFn cleanup_;

  mutable std::mutex mu_;
  mutable std::condition_variable changed_;
  uint64_t generation_ = 0;
  absl::Status broken_;  // a failed commit stops the table until it recovers (see above)
  bool loaded_ = false;  // the first load (a start) is done
  // Found due by a reload; run by the next RunCleanups (the reaper's tick at
  // the latest), whatever the call that reloaded went on to do.
  Cleanups deferred_cleanups_;
  int64_t next_job_id_ = 1;
  int64_t next_worker_id_ = 1;
  std::map<int64_t, JobState> jobs_;                       // by id: oldest first
  std::set<int64_t> runnable_;                             // jobs with a ready task
  std::set<std::tuple<int64_t, int64_t, int>> deadlines_;  // (deadline, job, task)
  std::map<int64_t, WorkerState> workers_;
  TaskCounters counters_;
  LatencyHistogram lease_latency_;
};

}  // namespace wavebake
