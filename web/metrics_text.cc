#include "web/metrics_text.h"

#include <cstdio>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"

namespace wavebake::web {
namespace {

void Family(std::string& out, const char* name, const char* type, const char* help) {
  absl::StrAppend(&out, "# HELP ", name, " ", help, "\n# TYPE ", name, " ", type, "\n");
}

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string Lower(const char* s) { return absl::AsciiStrToLower(s); }

void TaskFamily(std::string& out, const char* name, const char* help,
                const std::array<int64_t, 3>& by_kind) {
  Family(out, name, "counter", help);
  for (int k = 0; k < 3; ++k) {
    absl::StrAppend(&out, name, "{kind=\"", Lower(TaskKindName(static_cast<TaskKind>(k + 1))),
                    "\"} ", by_kind[k], "\n");
  }
}

void LatencyFamily(std::string& out, const LatencyHistogram::Snapshot& h) {
  const char* name = "wavebake_lease_latency_seconds";
  Family(out, name, "histogram",
         "Time the coordinator takes to answer a worker's Lease call (lock wait and commit "
         "included).");
  int64_t cumulative = 0;
  for (size_t i = 0; i < kLeaseLatencyBuckets.size(); ++i) {
    cumulative += h.counts[i];
    absl::StrAppend(&out, name, "_bucket{le=\"", Number(kLeaseLatencyBuckets[i]), "\"} ",
                    cumulative, "\n");
  }
  absl::StrAppend(&out, name, "_bucket{le=\"+Inf\"} ", h.count, "\n");
  absl::StrAppend(&out, name, "_sum ", Number(h.sum_seconds), "\n");
  absl::StrAppend(&out, name, "_count ", h.count, "\n");
}

template <typename Value>
void PerJob(std::string& out, const SchedulerSnapshot& s, const char* name, const char* help,
            Value value) {
  Family(out, name, "gauge", help);
  for (const JobTaskCounts& j : s.jobs) {
    absl::StrAppend(&out, name, "{job=\"", j.id, "\"} ", value(j), "\n");
  }
}

}  // namespace

std::string MetricsText(const SchedulerSnapshot& s) {
  std::string out;
  Family(out, "wavebake_jobs", "gauge", "Jobs the coordinator holds, by phase.");
  for (int p = 0; p < 7; ++p) {
    absl::StrAppend(&out, "wavebake_jobs{phase=\"", Lower(PhaseName(static_cast<Phase>(p + 1))),
                    "\"} ", s.jobs_by_phase[p], "\n");
  }
  TaskFamily(out, "wavebake_tasks_leased_total", "Task leases granted, by task kind.",
             s.tasks.leased);
  TaskFamily(out, "wavebake_tasks_completed_total",
             "Task results accepted (each task is completed once), by task kind.",
             s.tasks.completed);
  TaskFamily(out, "wavebake_tasks_failed_total", "Task failures reported by workers, by kind.",
             s.tasks.failed);
  TaskFamily(out, "wavebake_tasks_expired_total",
             "Task leases that expired without a heartbeat, by kind.", s.tasks.expired);
  Family(out, "wavebake_rays_traced_total", "counter", "Rays traced by completed tasks.");
  absl::StrAppend(&out, "wavebake_rays_traced_total ", s.rays_traced, "\n");
  LatencyFamily(out, s.lease_latency);
  Family(out, "wavebake_workers_alive", "gauge",
         "Workers seen within one lease period and not excluded.");
  absl::StrAppend(&out, "wavebake_workers_alive ", s.workers_alive, "\n");
  Family(out, "wavebake_workers_registered", "gauge", "Workers ever registered.");
  absl::StrAppend(&out, "wavebake_workers_registered ", s.workers_registered, "\n");
  Family(out, "wavebake_workers_excluded", "gauge", "Workers excluded after repeated failures.");
  absl::StrAppend(&out, "wavebake_workers_excluded ", s.workers_excluded, "\n");
  PerJob(out, s, "wavebake_job_tasks_done", "Done tasks of a job (as `wavebake status`).",
         [](const JobTaskCounts& j) { return j.tasks_done; });
  PerJob(out, s, "wavebake_job_tasks_total", "Tasks of a job: tiles + groups + 1.",
         [](const JobTaskCounts& j) { return j.tasks_total; });
  PerJob(out, s, "wavebake_job_tasks_leased", "Tasks of a job leased now.",
         [](const JobTaskCounts& j) { return j.leased_tasks; });
  PerJob(out, s, "wavebake_job_rays_traced", "Rays of a job, live leases included.",
         [](const JobTaskCounts& j) { return j.rays_traced; });
  return out;
}

}  // namespace wavebake::web
