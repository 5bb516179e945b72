#pragma once
// Jobs and events as the monitor's pages read them. A job is the one JSON
// shape of a job (driver/jobs/job_json.h), the same as `wavebake status --json`
// and Python's dicts.
#include <nlohmann/json.hpp>
#include <span>

#include "wavebake.pb.h"

namespace wavebake::web {

// The Job message: {"id", "request": {...}, "phase" ("BAKING"...), ...,
//  "eta_seconds" (< 0: unknown), ...}
nlohmann::json JobJson(const v1::Job& job);
nlohmann::json JobsJson(std::span<const v1::Job> jobs);

// {"seq", "unix_ms", "kind" ("TASK_DONE"...), "phase", "task_kind",
//  "task_index", "worker", "message", "tasks_done", "tasks_total"}
nlohmann::json EventJson(const v1::JobEvent& event);

}  // namespace wavebake::web
