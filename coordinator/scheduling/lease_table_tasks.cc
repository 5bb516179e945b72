// LeaseTable, worker side (DESIGN.md §4): register, lease, heartbeat,
// complete, fail, and the expiry of leases that were not renewed in time.
#include <algorithm>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "coordinator/scheduling/lease_table.h"
#include "coordinator/service/worker_errors.h"

namespace wavebake {

absl::StatusOr<int64_t> LeaseTable::RegisterWorker(std::string name, int threads) {
  int64_t id = 0;
  {
    std::lock_guard lock(mu_);
    if (absl::Status s = RecoverLocked(); !s.ok()) return s;
    id = next_worker_id_++;
    WorkerState w;
    w.rec = {
        .id = id, .name = std::move(name), .threads = threads, .registered_ms = clock_->NowMs()};
    // last_seen_ms stays 0 until its first Lease or Heartbeat: a worker checks
    // its store root between Register and its first Lease, and one that fails
    // the check exits without ever counting as alive in /metrics.
    Transition tx;
    tx.workers.push_back(w.rec);
    if (absl::Status s = CommitLocked(tx); !s.ok()) return s;
    workers_[id] = std::move(w);  // known once the database holds it
  }
  RunCleanups({});  // what a recovery found due
  return id;
}

absl::Status LeaseTable::RefusedLocked(const WorkerState& w) const {
  if (!w.rec.excluded) return absl::OkStatus();
  return ExcludedWorkerError(w.rec.id, w.rec.consecutive_failures);
}

// The lowest ready task of the oldest job that has one, or nullopt.
std::optional<LeaseGrant> LeaseTable::LeaseOneLocked(int64_t worker_id, int64_t now,
                                                     Transition& tx) {
  if (runnable_.empty()) return std::nullopt;
  JobState& js = jobs_.at(*runnable_.begin());  // oldest job with a ready task
  const int idx = *js.ready.begin();            // its lowest ready task
  js.ready.erase(js.ready.begin());
  if (js.ready.empty()) runnable_.erase(js.rec.id);
  if (js.rec.phase == Phase::kQueued) {
    js.rec.phase = Phase::kBaking;
    js.rec.started_ms = now;
    js.stages[0].opened_ms = now;
    tx.jobs.push_back(js.rec);
    AddEvent(js, tx, EventKind::kPhase);
  }
  TaskRecord& t = js.tasks[idx];
  t.state = TaskState::kLeased;
  t.worker_id = absl::StrCat(worker_id);
  ++t.attempts;
  const int64_t deadline = now + options_.lease_ms;
  js.leases[idx] = {
      .worker_id = worker_id, .attempt = t.attempts, .deadline_ms = deadline, .granted_ms = now};
  js.peak_leases = std::max(js.peak_leases, static_cast<int>(js.leases.size()));
  ++counters_.leased[static_cast<int>(t.kind) - 1];
  deadlines_.emplace(deadline, js.rec.id, idx);
  tx.tasks.push_back(t);
  AddEvent(js, tx, EventKind::kTaskLeased, &t, {}, worker_id);
  const LeaseKey key{js.rec.id, idx, t.attempts};
  return LeaseGrant{.lease_id = FormatLeaseId(key),
                    .key = key,
                    .kind = t.kind,
                    .kind_index = t.kind_index,
                    .deadline_ms = deadline,
                    .request = js.rec.request,
                    .store_path = js.rec.store_path,
                    .tiles = js.rec.tiles,
                    .groups = js.rec.groups};
}

absl::StatusOr<std::optional<LeaseGrant>> LeaseTable::Lease(int64_t worker_id) {
  absl::StatusOr<ExchangeResult> r = Exchange(worker_id, {}, 1);
  if (!r.ok()) return r.status();
  if (r->grants.empty()) return std::nullopt;
  return std::move(r->grants.front());
}

absl::StatusOr<ExchangeResult> LeaseTable::Exchange(int64_t worker_id,
                                                    std::span<const Completion> done,
                                                    int max_tasks) {
  // The call's whole time (a Lease is an Exchange): lock wait and commit included.
  LatencyHistogram::Timer timer(lease_latency_);
  Cleanups cleanups;
  ExchangeResult result;
  absl::Status refused;
  {
    std::lock_guard lock(mu_);
    if (absl::Status s = RecoverLocked(); !s.ok()) return s;
    auto w = workers_.find(worker_id);
    if (w == workers_.end()) {
      return UnknownWorkerError(worker_id);
    }
    const int64_t now = clock_->NowMs();
    Transition tx;
    ExpireLocked(now, tx, cleanups);  // may exclude this worker
    w->second.last_seen_ms = now;
    for (const Completion& c : done) {
      absl::StatusOr<bool> accepted = CompleteLocked(worker_id, c.key, c.report, tx, cleanups);
      result.accepted.push_back(accepted.ok() && *accepted);
    }
    refused = RefusedLocked(w->second);
    while (refused.ok() && static_cast<int>(result.grants.size()) < max_tasks) {
      std::optional<LeaseGrant> grant = LeaseOneLocked(worker_id, now, tx);
      if (!grant) break;
      result.grants.push_back(std::move(*grant));
    }
    if (absl::Status s = CommitLocked(tx); !s.ok()) return s;
  }
  RunCleanups(std::move(cleanups));
  if (!refused.ok()) return refused;
  return result;
}

absl::StatusOr<HeartbeatResult> LeaseTable::Heartbeat(int64_t worker_id,
                                                      std::span<const LeaseProgressReport> leases) {
  Cleanups cleanups;
  HeartbeatResult result;
  {
    std::lock_guard lock(mu_);
    if (absl::Status s = RecoverLocked(); !s.ok()) return s;
    auto w = workers_.find(worker_id);
    if (w == workers_.end()) {
      return UnknownWorkerError(worker_id);
    }
    const int64_t now = clock_->NowMs();
    Transition tx;
    ExpireLocked(now, tx, cleanups);  // a lease past its deadline is gone, even if renewed now
    w->second.last_seen_ms = now;
    result.deadline_ms = now + options_.lease_ms;
    for (const LeaseProgressReport& p : leases) {
      auto job = jobs_.find(p.key.job_id);
      LiveLease* lease = nullptr;
      if (job != jobs_.end()) {
        auto it = job->second.leases.find(p.key.task);
        if (it != job->second.leases.end() && it->second.attempt == p.key.attempt &&
            it->second.worker_id == worker_id) {
          lease = &it->second;
        }
      }
      if (!lease) {
        result.cancelled.push_back(p.key);  // expired, superseded or never granted
        continue;
      }
      JobState& js = job->second;
      if (IsTerminal(js.rec.phase)) {  // cancelled or failed: stop the worker, then clean up
        DropLease(js, p.key.task);
        MaybeCleanup(js, cleanups);
        result.cancelled.push_back(p.key);
        continue;
      }
      deadlines_.erase({lease->deadline_ms, js.rec.id, p.key.task});
      lease->deadline_ms = result.deadline_ms;
      deadlines_.emplace(result.deadline_ms, js.rec.id, p.key.task);
      js.live_rays += p.rays_traced - lease->rays_traced;
      js.live_bytes += p.bytes_written - lease->bytes_written;
      lease->rays_traced = p.rays_traced;
      lease->bytes_written = p.bytes_written;
      result.renewed.push_back(p.key);
    }
    if (absl::Status s = CommitLocked(tx); !s.ok()) return s;  // also wakes Watch for progress
  }
  RunCleanups(std::move(cleanups));
  return result;
}

absl::StatusOr<bool> LeaseTable::Complete(int64_t worker_id, const LeaseKey& key,
                                          const TaskReport& report) {
  Cleanups cleanups;
  absl::StatusOr<bool> accepted;
  {
    std::lock_guard lock(mu_);
    if (absl::Status s = RecoverLocked(); !s.ok()) return s;
    if (!workers_.contains(worker_id)) {
      return UnknownWorkerError(worker_id);
    }
    Transition tx;
    accepted = CompleteLocked(worker_id, key, report, tx, cleanups);
    if (absl::Status s = CommitLocked(tx); !s.ok()) return s;
  }
  RunCleanups(std::move(cleanups));
  return accepted;
}

absl::StatusOr<bool> LeaseTable::CompleteLocked(int64_t worker_id, const LeaseKey& key,
                                                const TaskReport& report, Transition& tx,
                                                Cleanups& cleanups) {
  auto job = jobs_.find(key.job_id);
  if (job == jobs_.end()) {
    return absl::NotFoundError(absl::StrCat("lease_id: job ", key.job_id, " not found"));
  }
  JobState& js = job->second;
  if (IsTerminal(js.rec.phase)) {
    auto it = js.leases.find(key.task);  // a cancelled or failed job's straggler
    if (it != js.leases.end() && it->second.attempt == key.attempt) DropLease(js, key.task);
    MaybeCleanup(js, cleanups);
    return false;
  }
  if (key.task >= static_cast<int>(js.tasks.size()) || key.attempt > js.tasks[key.task].attempts) {
    return absl::NotFoundError(
        absl::StrCat("lease_id: lease ", FormatLeaseId(key), " was never granted"));
  }
  TaskRecord& t = js.tasks[key.task];
  if (t.state == TaskState::kDone) return false;
  const int stage = static_cast<int>(t.kind) - 1;
  if (auto it = js.leases.find(key.task); it != js.leases.end()) {  // ours or a later grant's
    if (it->second.attempt ==
        key.attempt) {  // timed from its grant (coordinator/scheduling/eta_model.h)
      ++js.stages[stage].measured;
      js.stages[stage].measured_seconds += (clock_->NowMs() - it->second.granted_ms) / 1000.0;
    }
    DropLease(js, key.task);
  }
  ++counters_.completed[stage];
  if (t.state == TaskState::kPending && js.ready.erase(key.task) && js.ready.empty()) {
    runnable_.erase(js.rec.id);  // a late result of an expired lease
  }
  t.state = TaskState::kDone;
  t.worker_id = absl::StrCat(worker_id);
  t.rays_traced = report.rays_traced;
  t.bytes_written = report.bytes_written;
  t.stats_json = report.stats_json;
  ++js.tasks_done;
  if (t.kind == TaskKind::kBakeTile) ++js.tiles_done;
  if (t.kind == TaskKind::kTransformColumns) ++js.groups_done;
  // The last FINALIZE task's stats are the store's (its shards report none).
  if (t.index == js.rec.finalize_last()) js.rec.stats_json = report.stats_json;
  js.rec.rays_traced += report.rays_traced;
  js.rec.bytes_written += report.bytes_written;
  tx.tasks.push_back(t);
  WorkerRecord& w = workers_.at(worker_id).rec;
  if (w.consecutive_failures != 0) {  // a success ends a run of failures
    w.consecutive_failures = 0;
    tx.workers.push_back(w);
  }
  AddEvent(js, tx, EventKind::kTaskDone, &t, {}, worker_id);
  AdvanceStage(js, tx);  // may free js.tasks (job DONE): t is not used below
  tx.jobs.push_back(js.rec);
  return true;
}

absl::StatusOr<bool> LeaseTable::Fail(int64_t worker_id, const LeaseKey& key,
                                      absl::string_view reason, Failure failure) {
  Cleanups cleanups;
  bool counted = false;
  {
    std::lock_guard lock(mu_);
    if (absl::Status s = RecoverLocked(); !s.ok()) return s;
    if (!workers_.contains(worker_id)) {
      return UnknownWorkerError(worker_id);
    }
    auto job = jobs_.find(key.job_id);
    if (job == jobs_.end()) {
      return absl::NotFoundError(absl::StrCat("lease_id: job ", key.job_id, " not found"));
    }
    JobState& js = job->second;
    auto it = js.leases.find(key.task);
    if (it != js.leases.end() && it->second.attempt == key.attempt &&
        it->second.worker_id == worker_id) {
      DropLease(js, key.task);
      Transition tx;
      if (!IsTerminal(js.rec.phase)) {
        const bool permanent = failure == Failure::kPermanent;
        if (!permanent) ChargeWorker(worker_id, js, tx);
        ++counters_.failed[static_cast<int>(js.tasks[key.task].kind) - 1];
        ChargeTask(js, key.task, EventKind::kTaskFailed,
                   absl::StrCat("worker ", worker_id, ": ", reason), worker_id, tx, permanent);
        counted = true;
      }
      if (absl::Status s = CommitLocked(tx); !s.ok()) return s;
      MaybeCleanup(js, cleanups);
    }
  }
  RunCleanups(std::move(cleanups));
  return counted;
}

absl::Status LeaseTable::ExpireLeases() {
  Cleanups cleanups;
  {
    std::lock_guard lock(mu_);
    if (absl::Status s = RecoverLocked(); !s.ok()) return s;
    Transition tx;
    ExpireLocked(clock_->NowMs(), tx, cleanups);
    if (absl::Status s = CommitLocked(tx); !s.ok()) return s;
  }
  RunCleanups(std::move(cleanups));
  return absl::OkStatus();
}

// §4: "A lease that is not renewed in time returns its task to the queue".
void LeaseTable::ExpireLocked(int64_t now, Transition& tx, Cleanups& cleanups) {
  while (!deadlines_.empty() && std::get<0>(*deadlines_.begin()) <= now) {
    const auto [deadline, job_id, task] = *deadlines_.begin();
    JobState& js = jobs_.at(job_id);
    const int64_t worker_id = js.leases.at(task).worker_id;
    DropLease(js, task);
    if (!IsTerminal(js.rec.phase)) {
      ++counters_.expired[static_cast<int>(js.tasks[task].kind) - 1];
      ChargeWorker(worker_id, js, tx);
      ChargeTask(js, task, EventKind::kLeaseExpired,
                 absl::StrCat("worker ", worker_id, ": lease expired"), worker_id, tx);
    }
    MaybeCleanup(js, cleanups);
  }
}

void LeaseTable::DropLease(JobState& js, int task) {
  auto it = js.leases.find(task);
  deadlines_.erase({it->second.deadline_ms, js.rec.id, task});
  js.live_rays -= it->second.rays_traced;
  js.live_bytes -= it->second.bytes_written;
  js.leases.erase(it);
}

void LeaseTable::ChargeWorker(int64_t worker_id, JobState& js, Transition& tx) {
  WorkerRecord& w = workers_.at(worker_id).rec;
  ++w.consecutive_failures;
  if (w.consecutive_failures >= options_.worker_failure_limit && !w.excluded) {
    w.excluded = true;
    AddEvent(js, tx, EventKind::kWorkerExcluded, nullptr,
             absl::StrCat("worker ", worker_id, " excluded after ", w.consecutive_failures,
                          " consecutive failures"),
             worker_id);
  }
  tx.workers.push_back(w);
}

// A failure or an expiry: the task goes back to pending, or, at max_attempts
// or when permanent, fails the job with the reason (§4).
void LeaseTable::ChargeTask(JobState& js, int task, EventKind kind, std::string reason,
                            int64_t worker_id, Transition& tx, bool permanent) {
  TaskRecord& t = js.tasks[task];
  t.state = TaskState::kPending;
  t.worker_id.clear();
  ++t.failures;
  t.last_error = reason;
  tx.tasks.push_back(t);
  AddEvent(js, tx, kind, &t, reason, worker_id);
  if (permanent || t.failures >= js.rec.max_attempts) {
    EndJob(js, Phase::kFailed,
           permanent
               ? absl::StrCat(TaskKindName(t.kind), " ", t.kind_index,
                              " failed, not retried (its input, or a full disk): ", reason)
               : absl::StrCat(TaskKindName(t.kind), " ", t.kind_index, " failed ", t.failures,
                              " times (max_attempts ", js.rec.max_attempts, "); last: ", reason),
           tx);
    tx.jobs.push_back(js.rec);
    return;
  }
  js.ready.insert(task);
  runnable_.insert(js.rec.id);
}

}  // namespace wavebake
