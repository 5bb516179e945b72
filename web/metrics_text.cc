#include "web/metrics_text.h"

#include <cstdio>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "wavebake_build_info.h"

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
    if (IsTerminal(j.phase)) continue;  // finished jobs are counted in wavebake_jobs only
    absl::StrAppend(&out, name, "{job_id=\"", j.id, "\"} ", value(j), "\n");
  }
}

void Sample(std::string& out, const char* name, const char* type, const char* help,
            const std::string& value) {
  Family(out, name, type, help);
  absl::StrAppend(&out, name, " ", value, "\n");
}

void ProcessFamilies(std::string& out, const ProcessStats& p) {
  Sample(out, "process_cpu_seconds_total", "counter",
         "Total user and system CPU time spent in seconds.", Number(p.cpu_seconds));
  Sample(out, "process_resident_memory_bytes", "gauge", "Resident memory size in bytes.",
         absl::StrCat(p.resident_bytes));
  Sample(out, "process_virtual_memory_bytes", "gauge", "Virtual memory size in bytes.",
         absl::StrCat(p.virtual_bytes));
  Sample(out, "process_open_fds", "gauge", "Number of open file descriptors.",
         absl::StrCat(p.open_fds));
  if (p.max_fds > 0) {
    Sample(out, "process_max_fds", "gauge", "Maximum number of open file descriptors.",
           absl::StrCat(p.max_fds));
  }
  Sample(out, "process_start_time_seconds", "gauge",
         "Start time of the process since unix epoch in seconds.", Number(p.start_time_seconds));
}

}  // namespace

std::string MetricsText(const SchedulerSnapshot& s, const ProcessStats* process) {
  std::string out;
  Family(out, "wavebake_build_info", "gauge",
         "Always 1; the labels name the build (revision: the git commit it was configured from).");
  absl::StrAppend(&out, "wavebake_build_info{version=\"", WB_BUILD_VERSION, "\",revision=\"",
                  WB_BUILD_REVISION, "\"} 1\n");
  Family(out, "wavebake_jobs", "gauge",
         "Jobs the coordinator holds, by phase (finished ones are summed only here).");
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
         "Workers not excluded that leased or heartbeated within one lease period (a worker "
         "counts only after its store-root check, which precedes its first lease).");
  absl::StrAppend(&out, "wavebake_workers_alive ", s.workers_alive, "\n");
  Family(out, "wavebake_workers_registered_total", "counter",
         "Worker registrations the coordinator's database holds (records are never removed).");
  absl::StrAppend(&out, "wavebake_workers_registered_total ", s.workers_registered, "\n");
  Family(out, "wavebake_workers_excluded", "gauge", "Workers excluded after repeated failures.");
  absl::StrAppend(&out, "wavebake_workers_excluded ", s.workers_excluded, "\n");
  PerJob(out, s, "wavebake_job_tasks_done", "Done tasks of a live job (as `wavebake status`).",
         [](const JobTaskCounts& j) { return j.tasks_done; });
  PerJob(out, s, "wavebake_job_tasks", "Tasks of a live job: tiles + groups + FINALIZE.",
         [](const JobTaskCounts& j) { return j.tasks_total; });
  PerJob(out, s, "wavebake_job_tasks_leased", "Tasks of a live job leased now.",
         [](const JobTaskCounts& j) { return j.leased_tasks; });
  PerJob(out, s, "wavebake_job_rays_traced", "Rays of a live job, running leases included.",
         [](const JobTaskCounts& j) { return j.rays_traced; });
  if (process) ProcessFamilies(out, *process);
  return out;
}

}  // namespace wavebake::web
