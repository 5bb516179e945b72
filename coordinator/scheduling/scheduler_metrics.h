#pragma once
// What the scheduler counts for operators (DESIGN.md §4: the coordinator
// serves `/metrics`): task transitions by kind, the time a Lease call takes,
// and a snapshot of jobs and workers. The LeaseTable updates the counters
// where the transitions happen; the web layer formats a snapshot in the
// Prometheus text format. Counters cover this process's lifetime (a restart
// starts them at 0, which Prometheus reads as a counter reset).
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include "coordinator/scheduling/job_types.h"

namespace wavebake {

// Upper bounds (seconds) of the lease latency histogram's buckets; +Inf is
// implied. A Lease takes the table lock and commits one SQLite transaction,
// so its latency lives between tens of microseconds and a slow disk's sync.
inline constexpr std::array<double, 12> kLeaseLatencyBuckets = {
    0.0001, 0.00025, 0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 1.0};

// A Prometheus histogram without a lock: per-bucket (non-cumulative) counts.
class LatencyHistogram {
 public:
  void Observe(double seconds);
  struct Snapshot {
    std::array<int64_t, kLeaseLatencyBuckets.size() + 1> counts{};  // last: above every bound
    int64_t count = 0;
    double sum_seconds = 0;
  };
  Snapshot Read() const;

  // Observes the time from its construction to its destruction.
  class Timer {
   public:
    explicit Timer(LatencyHistogram& h) : histogram_(h), start_(std::chrono::steady_clock::now()) {}
    ~Timer() {
      histogram_.Observe(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    }
    Timer(const Timer&) = delete;
    Timer& operator=(const Timer&) = delete;

   private:
    LatencyHistogram& histogram_;
    std::chrono::steady_clock::time_point start_;
  };

 private:
  std::array<std::atomic<int64_t>, kLeaseLatencyBuckets.size() + 1> counts_{};
  std::atomic<int64_t> sum_ns_{0};
};

// Task transitions, by task kind (index: TaskKind − 1).
struct TaskCounters {
  std::array<int64_t, 3> leased{}, completed{}, failed{}, expired{};
};

// A job's numbers as `wavebake status` shows them.
struct JobTaskCounts {
  int64_t id = 0;
  Phase phase = Phase::kQueued;
  int tasks_done = 0, tasks_total = 0, leased_tasks = 0;
  int64_t rays_traced = 0;
};

struct SchedulerSnapshot {
  TaskCounters tasks;
  // Jobs in memory by phase (index: Phase − 1).
  std::array<int64_t, 7> jobs_by_phase{};
  // Rays of completed tasks (monotone, unlike the live count of a job,
  // which drops when an unfinished lease expires).
  int64_t rays_traced = 0;
  // alive: not excluded, and a Lease or Heartbeat within one lease period
  // (Register alone does not count: the worker's checks come after it).
  int workers_registered = 0, workers_alive = 0, workers_excluded = 0;
  LatencyHistogram::Snapshot lease_latency;
  // Live (not terminal) jobs, newest first, at most the limit asked for.
  std::vector<JobTaskCounts> jobs;
};

}  // namespace wavebake
