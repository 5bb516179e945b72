#pragma once
// Jobs and events as the monitor's pages read them (JSON; numbers stay
// numbers, unlike the proto JSON mapping's int64 strings).
#include <nlohmann/json.hpp>
#include <span>

#include "wavebake.pb.h"

namespace wavebake::web {

// {"id", "phase" ("BAKING"...), "scene", "layout", "light_res", "store_path",
//  "tiles", "groups", "tasks_done", "tasks_total", "leased_tasks",
//  "rays_traced", "rays_estimate", "rays_per_second", "bytes_written",
//  "eta_seconds" (null: unknown), "error", "created_ms", "started_ms",
//  "finished_ms", "ended"}
nlohmann::json JobJson(const v1::Job& job);
nlohmann::json JobsJson(std::span<const v1::Job> jobs);

// {"seq", "unix_ms", "kind" ("TASK_DONE"...), "phase", "task_kind",
//  "task_index", "worker", "message", "tasks_done", "tasks_total"}
nlohmann::json EventJson(const v1::JobEvent& event);

}  // namespace wavebake::web
