#pragma once
// GET /metrics (DESIGN.md §4): the scheduler's numbers in the Prometheus
// text exposition format 0.0.4 (one # HELP and # TYPE per family, counters
// ending in _total, histogram buckets cumulative up to le="+Inf").
#include <string>

#include "coordinator/scheduler_metrics.h"

namespace wavebake::web {

inline constexpr char kMetricsContentType[] = "text/plain; version=0.0.4; charset=utf-8";

// Families: wavebake_jobs{phase}, wavebake_tasks_{leased,completed,failed,
// expired}_total{kind}, wavebake_rays_traced_total,
// wavebake_lease_latency_seconds (histogram), wavebake_workers_{alive,
// registered,excluded}, and per job (the newest ones the snapshot holds)
// wavebake_job_tasks_{done,total,leased}{job}, wavebake_job_rays_traced{job}.
std::string MetricsText(const SchedulerSnapshot& snapshot);

}  // namespace wavebake::web
