// LeaseTable, job side: loading and resuming, submitting, stages, cancel,
// cleanup, live numbers. The worker side (lease, heartbeat, complete, fail,
// expiry) is in lease_table_tasks.cc.
#include "coordinator/scheduling/lease_table.h"

#include <algorithm>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "coordinator/scheduling/eta_model.h"

namespace wavebake {
namespace {

// What a RESUMED event says happened.
constexpr absl::string_view kRestarted = "coordinator restarted";
constexpr absl::string_view kRecovered =
    "the database refused a change (a full disk?), state reloaded from it";

// Task index range [begin, end) of the stage a phase stands for (§2).
std::pair<int, int> StageRange(const JobRecord& r, Phase phase) {
  switch (phase) {
    case Phase::kQueued:
    case Phase::kBaking:
      return {0, r.tiles};
    case Phase::kTransforming:
      return {r.tiles, r.tiles + r.groups};
    case Phase::kFinalizing:
      return {r.tiles + r.groups, r.tasks_total()};
    default:
      return {0, 0};
  }
}

bool SafeRelativePath(const std::string& p) {
  if (p.empty() || p.front() == '/' || p.find('\\') != p.npos) return false;
  for (size_t start = 0; start <= p.size();) {
    const size_t end = std::min(p.find('/', start), p.size());
    const absl::string_view part(p.data() + start, end - start);
    if (part.empty() || part == "." || part == "..") return false;
    start = end + 1;
  }
  return true;
}

// Stage index (tiles 0, groups 1, finalize 2) of a phase or a task kind.
int StageOf(Phase phase) {
  return phase == Phase::kTransforming ? 1 : phase == Phase::kFinalizing ? 2 : 0;
}
int StageOf(TaskKind kind) { return static_cast<int>(kind) - 1; }

}  // namespace

absl::StatusOr<std::unique_ptr<LeaseTable>> LeaseTable::Create(JobStore* store, const Clock* clock,
                                                               LeaseTableOptions options,
                                                               CleanupFn cleanup) {
  if (options.lease_ms <= 0) return absl::InvalidArgumentError("lease_ms: must be positive");
  auto table =
      std::make_unique<LeaseTable>(Key{}, store, clock, std::move(options), std::move(cleanup));
  if (store) {
    if (absl::Status s = table->Load(); !s.ok()) return s;
  }
  return table;
}

LeaseTable::LeaseTable(Key, JobStore* store, const Clock* clock, LeaseTableOptions options,
                       CleanupFn cleanup)
    : store_(store),
      clock_(clock ? clock : SystemClock::Get()),
      options_(std::move(options)),
      cleanup_(std::move(cleanup)) {}

absl::Status LeaseTable::Load() {
  {
    std::lock_guard lock(mu_);
    broken_ = absl::UnavailableError("not loaded yet");
    if (absl::Status s = RecoverLocked(); !s.ok()) return s;
  }
  RunCleanups({});
  return absl::OkStatus();
}

absl::Status LeaseTable::ReloadLocked(absl::string_view why, Transition& tx) {
  absl::StatusOr<StoreSnapshot> snap = store_->Load();
  if (!snap.ok()) return snap.status();
  // What the database does not hold but must survive: when workers were last
  // seen, and the ids handed out (a reserved job id or a worker id whose
  // commit failed is never given again).
  std::map<int64_t, int64_t> last_seen;
  for (const auto& [id, w] : workers_) last_seen[id] = w.last_seen_ms;
  jobs_.clear();
  deferred_cleanups_.clear();  // scheduled again below if still due
  runnable_.clear();
  deadlines_.clear();
  workers_.clear();
  for (WorkerRecord& w : snap->workers) {
    next_worker_id_ = std::max(next_worker_id_, w.id + 1);
    WorkerState& ws = workers_[w.id];
    ws.rec = std::move(w);
    if (auto it = last_seen.find(ws.rec.id); it != last_seen.end()) ws.last_seen_ms = it->second;
  }
  for (JobRecord& rec : snap->jobs) {
    next_job_id_ = std::max(next_job_id_, rec.id + 1);
    JobState& js = jobs_[rec.id];
    js.rec = std::move(rec);
    js.last_event_seq = snap->last_event_seq[js.rec.id];
  }
  for (TaskRecord& t : snap->tasks) jobs_[t.job_id].tasks.push_back(std::move(t));
  for (auto& [id, js] : jobs_) {
    if (!IsTerminal(js.rec.phase)) {
      if (absl::Status s = ResumeJob(js, why, tx); !s.ok()) return s;
    }
    MaybeCleanup(js, deferred_cleanups_);  // a cleanup the previous run did not finish
  }
  return absl::OkStatus();
}

absl::Status LeaseTable::RecoverLocked() {
  if (broken_.ok() || !store_) return absl::OkStatus();
  Transition tx;
  absl::Status s = ReloadLocked(loaded_ ? kRecovered : kRestarted, tx);
  if (s.ok() && !(tx.jobs.empty() && tx.tasks.empty() && tx.events.empty())) s = store_->Commit(tx);
  broken_ = s;
  loaded_ = true;
  ++generation_;
  changed_.notify_all();
  return s;
}

// A job of a previous coordinator: its leases are void, so leased tasks are
// pending again without being charged an attempt (§4 "resumes after a restart").
absl::Status LeaseTable::ResumeJob(JobState& js, absl::string_view why, Transition& tx) {
  UpgradeFinalizeRows(js, tx);
  if (static_cast<int>(js.tasks.size()) != js.rec.tasks_total()) {
    return absl::DataLossError(absl::StrCat("job ", js.rec.id, ": ", js.tasks.size(),
                                            " task rows, expected ", js.rec.tasks_total()));
  }
  int requeued = 0;
  for (TaskRecord& t : js.tasks) {
    if (t.state == TaskState::kLeased) {
      t.state = TaskState::kPending;
      t.worker_id.clear();
      tx.tasks.push_back(t);
      ++requeued;
    }
    if (t.state != TaskState::kDone) continue;
    ++js.tasks_done;
    if (t.kind == TaskKind::kBakeTile) ++js.tiles_done;
    if (t.kind == TaskKind::kTransformColumns) ++js.groups_done;
  }
  QueueStage(js);
  // The stage's clock restarts here; earlier task times died with the old process.
  if (js.rec.started_ms > 0) js.stages[StageOf(js.rec.phase)].opened_ms = clock_->NowMs();
  AddEvent(js, tx, EventKind::kResumed, nullptr,
           absl::StrCat(why, "; ", requeued, " leased tasks back to pending"));
  return absl::OkStatus();
}

// A job planned before FINALIZE was split has one FINALIZE row (index tiles
// + groups) where the layout now has the shards and the last task: that row
// becomes shard 0 and the others are added, all pending (an unfinished job's
// FINALIZE is not done; the shards rewrite whatever a killed one-task
// FINALIZE wrote, byte for byte).
void LeaseTable::UpgradeFinalizeRows(JobState& js, Transition& tx) {
  const int first = js.rec.tiles + js.rec.groups;
  if (static_cast<int>(js.tasks.size()) != first + 1 || js.rec.tasks_total() == first + 1 ||
      js.tasks[first].kind != TaskKind::kFinalize || js.tasks[first].state == TaskState::kDone) {
    return;
  }
  const TaskRecord old = js.tasks[first];
  js.tasks.resize(js.rec.tasks_total());
  for (int i = first; i < js.rec.tasks_total(); ++i) {
    js.tasks[i] = {.job_id = js.rec.id,
                   .index = i,
                   .kind = TaskKind::kFinalize,
                   .kind_index = i - first,
                   .attempts = i == first ? old.attempts : 0,
                   .failures = i == first ? old.failures : 0};
    tx.tasks.push_back(js.tasks[i]);
  }
}

int64_t LeaseTable::ReserveJobId() {
  std::lock_guard lock(mu_);
  return next_job_id_++;
}

absl::StatusOr<JobInfo> LeaseTable::AddJob(int64_t id, std::string request, int max_attempts,
                                           const PlannedJob& plan) {
  // The plan comes from the caller's planner: its mistakes are internal errors.
  if (plan.tiles < 1 || plan.groups < 1 ||
      int64_t{plan.tiles} + plan.groups + FinalizeTasks(plan.groups) > options_.max_tasks_per_job) {
    return absl::InternalError(absl::StrCat("plan: ", plan.tiles, " tiles and ", plan.groups,
                                            " groups is not a valid plan"));
  }
  if (!SafeRelativePath(plan.store_path)) {
    return absl::InternalError(
        absl::StrCat("plan: store_path \"", plan.store_path, "\" is not a relative path"));
  }
  bool store_is_ours = false;
  absl::StatusOr<JobInfo> added =
      AddJobLocked(id, std::move(request), max_attempts, plan, store_is_ours);
  RunCleanups({});
  // A job that is not in the database is not anywhere: the store its planner
  // reserved is removed, so a failed submit leaves nothing behind, not even
  // on a full disk (it would hold space and block the name).
  if (!added.ok() && store_is_ours && cleanup_) cleanup_({.id = id, .store_path = plan.store_path});
  return added;
}

absl::StatusOr<JobInfo> LeaseTable::AddJobLocked(int64_t id, std::string request, int max_attempts,
                                                 const PlannedJob& plan, bool& store_is_ours) {
  std::lock_guard lock(mu_);
  if (jobs_.contains(id) || id <= 0 || id >= next_job_id_) {
    return absl::InternalError(absl::StrCat("job id ", id, " was not reserved"));
  }
  for (const auto& [other_id, other] : jobs_) {
    if (!IsTerminal(other.rec.phase) && other.rec.store_path == plan.store_path) {
      return absl::AlreadyExistsError(absl::StrCat("output_name: \"", plan.store_path,
                                                   "\" is the store of running job ", other_id));
    }
  }
  store_is_ours = true;  // reserved for this id, and no other job's
  if (absl::Status s = RecoverLocked(); !s.ok()) return s;
  // Built aside and published only once committed: a job the database
  // refused is never seen, listed or leased.
  JobState js;
  js.rec = {.id = id,
            .request = std::move(request),
            .phase = Phase::kQueued,
            .tiles = plan.tiles,
            .groups = plan.groups,
            .rays_estimate = plan.total_rays_estimate,
            .store_path = plan.store_path,
            .max_attempts = max_attempts,
            .created_ms = clock_->NowMs()};
  js.tasks.resize(js.rec.tasks_total());
  for (int i = 0; i < js.rec.tasks_total(); ++i) {
    TaskRecord& t = js.tasks[i];
    t.job_id = id;
    t.index = i;
    t.kind = i < plan.tiles                 ? TaskKind::kBakeTile
             : i < plan.tiles + plan.groups ? TaskKind::kTransformColumns
                                            : TaskKind::kFinalize;
    t.kind_index = t.kind == TaskKind::kBakeTile           ? i
                   : t.kind == TaskKind::kTransformColumns ? i - plan.tiles
                                                           : i - plan.tiles - plan.groups;
    if (t.kind == TaskKind::kBakeTile) js.ready.insert(i);
  }
  Transition tx;
  tx.jobs.push_back(js.rec);
  tx.tasks = js.tasks;
  AddEvent(js, tx, EventKind::kSubmitted);
  if (absl::Status s = CommitLocked(tx); !s.ok()) return s;
  JobState& added = jobs_[id] = std::move(js);
  runnable_.insert(id);
  return InfoLocked(added);
}

absl::StatusOr<JobInfo> LeaseTable::Get(int64_t id) const {
  std::lock_guard lock(mu_);
  auto it = jobs_.find(id);
  if (it == jobs_.end()) return absl::NotFoundError(absl::StrCat("job ", id, " not found"));
  return InfoLocked(it->second);
}

std::vector<JobInfo> LeaseTable::List(int limit, bool active_only) const {
  std::lock_guard lock(mu_);
  std::vector<JobInfo> out;
  for (auto it = jobs_.rbegin(); it != jobs_.rend() && static_cast<int>(out.size()) < limit; ++it) {
    if (!active_only || !IsTerminal(it->second.rec.phase)) out.push_back(InfoLocked(it->second));
  }
  return out;
}

absl::StatusOr<JobInfo> LeaseTable::Cancel(int64_t id) {
  Cleanups cleanups;
  JobInfo info;
  {
    std::lock_guard lock(mu_);
    if (absl::Status s = RecoverLocked(); !s.ok()) return s;
    auto it = jobs_.find(id);
    if (it == jobs_.end()) return absl::NotFoundError(absl::StrCat("job ", id, " not found"));
    JobState& js = it->second;
    if (js.rec.phase == Phase::kDone || js.rec.phase == Phase::kFailed) {
      return absl::FailedPreconditionError(
          absl::StrCat("job ", id, " already ended ", PhaseName(js.rec.phase)));
    }
    if (js.rec.phase != Phase::kCancelled) {
      Transition tx;
      EndJob(js, Phase::kCancelled, "cancelled", tx);
      tx.jobs.push_back(js.rec);
      // A failed commit restores the job as the database holds it (CommitLocked).
      if (absl::Status s = CommitLocked(tx); !s.ok()) return s;
      MaybeCleanup(js, cleanups);
    }
    info = InfoLocked(js);
  }
  RunCleanups(std::move(cleanups));
  return info;
}

// Opens the stage of `phase`: its pending tasks become leasable.
void LeaseTable::OpenStage(JobState& js, Phase phase, Transition& tx) {
  js.rec.phase = phase;
  js.stages[StageOf(phase)].opened_ms = clock_->NowMs();
  QueueStage(js);
  AddEvent(js, tx, EventKind::kPhase);
}

// The pending tasks of the job's stage become leasable; FINALIZE's last
// task only once every shard is done (it reads what they wrote).
void LeaseTable::QueueStage(JobState& js) {
  const auto [begin, end] = StageRange(js.rec, js.rec.phase);
  const int last = js.rec.finalize_last();
  for (int i = begin; i < end; ++i) {
    if (js.tasks[i].state != TaskState::kPending) continue;
    if (i == last && !ShardsDone(js)) continue;
    js.ready.insert(i);
  }
  if (!js.ready.empty()) runnable_.insert(js.rec.id);
}

bool LeaseTable::ShardsDone(const JobState& js) {
  const int done = js.tasks_done - js.tiles_done - js.groups_done;
  return done >= FinalizeShards(js.rec.groups);
}

// After a task is done: groups only once every tile is done, FINALIZE's
// shards once every group is (§2: the blocked transpose needs every tile's
// chunks), its last task once every shard is.
void LeaseTable::AdvanceStage(JobState& js, Transition& tx) {
  const JobRecord& r = js.rec;
  if ((r.phase == Phase::kBaking || r.phase == Phase::kQueued) && js.tiles_done == r.tiles) {
    OpenStage(js, Phase::kTransforming, tx);
  }
  if (r.phase == Phase::kTransforming && js.groups_done == r.groups) {
    OpenStage(js, Phase::kFinalizing, tx);
  } else if (r.phase == Phase::kFinalizing && ShardsDone(js) &&
             js.tasks[r.finalize_last()].state == TaskState::kPending &&
             !js.ready.contains(r.finalize_last())) {
    js.ready.insert(r.finalize_last());  // the shards are done: the last task's turn
    runnable_.insert(r.id);
  }
  if (r.phase == Phase::kFinalizing && js.tasks_done == r.tasks_total()) {
    EndJob(js, Phase::kDone, {}, tx);
  }
}

void LeaseTable::EndJob(JobState& js, Phase phase, std::string error, Transition& tx) {
  js.rec.phase = phase;
  js.rec.error = std::move(error);
  js.rec.finished_ms = clock_->NowMs();
  js.ready.clear();
  runnable_.erase(js.rec.id);
  AddEvent(js, tx, EventKind::kPhase, nullptr, js.rec.error);
  std::vector<TaskRecord>().swap(js.tasks);  // an ended job needs no tasks in memory
}

void LeaseTable::AddEvent(JobState& js, Transition& tx, EventKind kind, const TaskRecord* task,
                          std::string message, int64_t worker_id) {
  const JobInfo info = CountsLocked(js);  // events carry no rates (proto/wavebake.proto)
  EventRecord e{.job_id = js.rec.id,
                .seq = ++js.last_event_seq,
                .unix_ms = clock_->NowMs(),
                .kind = kind,
                .phase = js.rec.phase,
                .message = std::move(message),
                .tasks_done = info.tasks_done,
                .tasks_total = js.rec.tasks_total(),
                .rays_traced = info.rays_traced,
                .bytes_written = info.bytes_written};
  if (task) {
    e.task_kind = task->kind;
    e.task_index = task->kind_index;
  }
  if (worker_id > 0) e.worker_id = absl::StrCat(worker_id);
  if (kind == EventKind::kPhase && js.rec.phase == Phase::kDone) e.stats_json = js.rec.stats_json;
  tx.events.push_back(std::move(e));
}

JobInfo LeaseTable::CountsLocked(const JobState& js) const {
  const JobRecord& r = js.rec;
  return {.record = r,
          .tasks_done = r.phase == Phase::kDone ? r.tasks_total() : js.tasks_done,
          .leased_tasks = static_cast<int>(js.leases.size()),
          .rays_traced = r.rays_traced + js.live_rays,
          .bytes_written = r.bytes_written + js.live_bytes,
          .rays_estimate = r.rays_estimate};
}

JobInfo LeaseTable::InfoLocked(const JobState& js) const {
  const JobRecord& r = js.rec;
  JobInfo info = CountsLocked(js);
  // The planner's estimate bounds the rays from above (every sample, column
  // and direction: brute force); visibility refinement traces a part of it
  // that depends on the scene, often a tenth. The done tiles say which part:
  // while baking (every done task is a tile) their rays × tiles / done, once
  // every tile is done what they traced.
  if (r.phase == Phase::kBaking && js.tasks_done > 0) {
    info.rays_estimate = static_cast<int64_t>(static_cast<double>(r.rays_traced) * r.tiles /
                                              static_cast<double>(js.tasks_done));
  } else if (r.phase > Phase::kBaking && r.phase <= Phase::kDone) {
    info.rays_estimate = r.rays_traced;
  }
  if (r.started_ms <= 0) return info;
  const int64_t now = clock_->NowMs();
  const int64_t end_ms = IsTerminal(r.phase) ? r.finished_ms : now;
  const double elapsed = std::max<int64_t>(end_ms - r.started_ms, 1) / 1000.0;
  info.rays_per_second = info.rays_traced / elapsed;
  if (r.phase == Phase::kDone) info.eta_seconds = 0;
  if (!IsTerminal(r.phase)) info.eta_seconds = EtaLocked(js, info, now);
  return info;
}

// The inputs of coordinator/scheduling/eta_model.h from the job's tasks and leases.
double LeaseTable::EtaLocked(const JobState& js, const JobInfo& info, int64_t now_ms) const {
  const JobRecord& r = js.rec;
  EtaInputs in;
  in.current = StageOf(r.phase);
  in.parallelism = std::max(js.peak_leases, 1);
  // FINALIZE's tasks (shards and the last) count as one for the ETA model,
  // whose prior is for the stage as a whole (coordinator/scheduling/eta_model.h).
  const int counts[3] = {r.tiles, r.groups, 1};
  const int done[3] = {js.tiles_done, js.groups_done, js.tasks_done == r.tasks_total() ? 1 : 0};
  for (int s = 0; s < 3; ++s) {
    in.stages[s].tasks = counts[s];
    in.stages[s].done = done[s];
    in.stages[s].measured = js.stages[s].measured;
    in.stages[s].measured_seconds = js.stages[s].measured_seconds;
  }
  for (const auto& [task, lease] : js.leases) {
    const int s = StageOf(js.tasks[task].kind);
    in.stages[s].running.push_back(std::max<int64_t>(now_ms - lease.granted_ms, 0) / 1000.0);
  }
  const int64_t opened = js.stages[in.current].opened_ms;
  in.stage_elapsed = opened > 0 ? std::max<int64_t>(now_ms - opened, 0) / 1000.0 : 0;
  if (js.stages[1].opened_ms > 0 && r.started_ms > 0 && js.stages[0].opened_ms > 0) {
    in.tile_stage_seconds = (js.stages[1].opened_ms - js.stages[0].opened_ms) / 1000.0;
  }
  if (in.current == 0 && r.rays_estimate > 0) {
    in.tile_rays_fraction = static_cast<double>(info.rays_traced) / r.rays_estimate;
  }
  return EstimateEta(in);
}

SchedulerSnapshot LeaseTable::Metrics(int job_limit) const {
  SchedulerSnapshot snap;
  snap.lease_latency = lease_latency_.Read();
  std::lock_guard lock(mu_);
  snap.tasks = counters_;
  for (auto it = jobs_.rbegin(); it != jobs_.rend(); ++it) {
    const JobState& js = it->second;
    ++snap.jobs_by_phase[static_cast<int>(js.rec.phase) - 1];
    snap.rays_traced += js.rec.rays_traced;
    // Per-job series for live jobs only: finished ones are summed by phase.
    if (IsTerminal(js.rec.phase) || static_cast<int>(snap.jobs.size()) >= job_limit) continue;
    const JobInfo info = CountsLocked(js);
    snap.jobs.push_back({.id = js.rec.id,
                         .phase = js.rec.phase,
                         .tasks_done = info.tasks_done,
                         .tasks_total = js.rec.tasks_total(),
                         .leased_tasks = info.leased_tasks,
                         .rays_traced = info.rays_traced});
  }
  const int64_t now = clock_->NowMs();
  for (const auto& [id, w] : workers_) {
    ++snap.workers_registered;
    if (w.rec.excluded) {
      ++snap.workers_excluded;
    } else if (w.last_seen_ms > 0 && now - w.last_seen_ms <= options_.lease_ms) {
      ++snap.workers_alive;
    }
  }
  return snap;
}

void LeaseTable::MaybeCleanup(JobState& js, Cleanups& cleanups) {
  const Phase p = js.rec.phase;
  if ((p == Phase::kFailed || p == Phase::kCancelled) && js.leases.empty() && !js.rec.cleaned &&
      !js.cleanup_scheduled) {
    js.cleanup_scheduled = true;
    cleanups.push_back(js.rec);
  }
}

// Outside the lock: a cleanup removes files and may take a while.
void LeaseTable::RunCleanups(Cleanups cleanups) {
  {
    std::lock_guard lock(mu_);
    cleanups.insert(cleanups.end(), deferred_cleanups_.begin(), deferred_cleanups_.end());
    deferred_cleanups_.clear();
  }
  for (const JobRecord& rec : cleanups) {
    if (cleanup_) cleanup_(rec);
    std::lock_guard lock(mu_);
    // Stopped: the job is marked when the table recovers (its reload
    // schedules the cleanup again; removing twice is harmless).
    if (!broken_.ok()) continue;
    auto it = jobs_.find(rec.id);
    if (it == jobs_.end() || it->second.rec.cleaned) continue;
    it->second.rec.cleaned = true;
    Transition tx;
    tx.jobs.push_back(it->second.rec);
    (void)CommitLocked(tx);  // on failure the table is stopped; its recovery cleans again
  }
}

absl::Status LeaseTable::CommitLocked(Transition& tx) {
  ++generation_;
  changed_.notify_all();
  if (!store_ || (tx.jobs.empty() && tx.tasks.empty() && tx.events.empty() && tx.workers.empty())) {
    return absl::OkStatus();
  }
  absl::Status s = store_->Commit(tx);
  // A full disk, and the transition ends jobs whose stores no worker writes
  // any more: those stores are garbage whatever happens, and removing them
  // first is what lets the end be recorded (a FINALIZE that failed for want
  // of space, a cancel to make room). Then once more.
  if (s.code() == absl::StatusCode::kResourceExhausted && FreeEndedStoresLocked(tx)) {
    s = store_->Commit(tx);
  }
  if (s.ok()) return s;
  // Memory is ahead of the database: put it back as the database holds it,
  // and stop until a commit succeeds again (RecoverLocked, at the next call
  // or reaper tick). The reload's cleanups run at that recovery.
  broken_ = s;
  Transition resumed;
  (void)ReloadLocked(kRecovered, resumed);
  return s;
}

bool LeaseTable::FreeEndedStoresLocked(Transition& tx) {
  bool freed = false;
  for (JobRecord& rec : tx.jobs) {
    if (rec.phase != Phase::kFailed && rec.phase != Phase::kCancelled) continue;
    auto it = jobs_.find(rec.id);
    if (it == jobs_.end() || !it->second.leases.empty() || it->second.rec.cleaned) continue;
    JobState& js = it->second;
    if (cleanup_) cleanup_(js.rec);
    js.rec.cleaned = true;
    js.cleanup_scheduled = true;
    freed = true;
  }
  if (freed) {
    for (JobRecord& rec : tx.jobs) {
      auto it = jobs_.find(rec.id);
      if (it != jobs_.end() && it->second.rec.cleaned) rec.cleaned = true;
    }
  }
  return freed;
}

absl::Status LeaseTable::broken() const {
  std::lock_guard lock(mu_);
  return broken_;
}

uint64_t LeaseTable::generation() const {
  std::lock_guard lock(mu_);
  return generation_;
}

uint64_t LeaseTable::WaitForChange(uint64_t seen, int64_t timeout_ms) const {
  std::unique_lock lock(mu_);
  changed_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
                    [&] { return generation_ != seen; });
  return generation_;
}

absl::StatusOr<std::vector<EventRecord>> LeaseTable::ReadEvents(int64_t job_id, int64_t after_seq,
                                                                int limit) const {
  if (!store_) return std::vector<EventRecord>{};
  return store_->ReadEvents(job_id, after_seq, limit);
}

}  // namespace wavebake
