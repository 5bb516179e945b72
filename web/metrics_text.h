#pragma once
// GET /metrics (DESIGN.md §4): the scheduler's numbers in the Prometheus
// text exposition format 0.0.4, named by prometheus.io's conventions
// ("Metric and label naming", "Instrumentation"): one # HELP and # TYPE per
// family; counters end in _total and gauges do not; base units (seconds,
// bytes); no label named job or instance (Prometheus' target labels); the
// series bounded: per-job series only for live jobs, finished ones summed
// in wavebake_jobs{phase}.
#include <string>

#include "coordinator/scheduling/scheduler_metrics.h"
#include "web/process_metrics.h"

namespace wavebake::web {

inline constexpr char kMetricsContentType[] = "text/plain; version=0.0.4; charset=utf-8";

// Families: wavebake_build_info{version,revision} (always 1),
// wavebake_jobs{phase}, wavebake_tasks_{leased,completed,failed,
// expired}_total{kind}, wavebake_rays_traced_total,
// wavebake_lease_latency_seconds (histogram), wavebake_workers_{alive,
// excluded}, wavebake_workers_registered_total; per live job
// wavebake_job_tasks{,_done,_leased}{job_id}, wavebake_job_rays_traced{job_id};
// and process_* when `process` is given.
std::string MetricsText(const SchedulerSnapshot& snapshot, const ProcessStats* process = nullptr);

}  // namespace wavebake::web
