#pragma once
// The web monitor's view of a live Coordinator in this process: its lease
// table (jobs, events, metrics) and its store root. FrozenJob keeps one
// job's last state when the coordinator is about to go (`bake --serve`).
#include <filesystem>
#include <memory>
#include <string>

#include "coordinator/service/coordinator.h"
#include "coordinator/service/job_planner.h"
#include "web/job_source.h"

namespace wavebake::web {

// The coordinator must outlive the source; SourceSlot::Set tells when no
// request uses it any more. `planner` finds uploaded scenes (JobScene).
std::shared_ptr<JobSource> CoordinatorSource(Coordinator& coordinator, PlannerOptions planner);

// A copy of job `id` as `live` shows it now — the job, its events, the
// scheduler metrics, its scene — whose store is at `store_dir` (where the
// embedded bake publishes it). It can no longer be cancelled.
absl::StatusOr<std::shared_ptr<JobSource>> FrozenJob(const JobSource& live, const std::string& id,
                                                     std::filesystem::path store_dir);

}  // namespace wavebake::web
