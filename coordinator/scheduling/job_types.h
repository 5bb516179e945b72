#pragma once
// Plain records of the coordinator's state (DESIGN.md §2, §4): jobs, their
// tasks, the events of every transition, workers. JobStore persists them in
// SQLite; LeaseTable keeps the live copy. Enum values equal the wavebake.v1
// proto numbers (checked in proto_convert.cc) and are what SQLite stores.
#include <cstdint>
#include <functional>
#include <string>

#include "absl/status/statusor.h"
#include "core/bake/finalize_shards.h"

namespace wavebake {

namespace v1 {
class BakeRequest;
}

enum class Phase : int {
  kQueued = 1,
  kBaking = 2,
  kTransforming = 3,
  kFinalizing = 4,
  kDone = 5,
  kFailed = 6,
  kCancelled = 7,
};
inline bool IsTerminal(Phase p) { return p >= Phase::kDone; }
const char* PhaseName(Phase p);

enum class TaskKind : int { kBakeTile = 1, kTransformColumns = 2, kFinalize = 3 };
const char* TaskKindName(TaskKind k);

// kPending covers "ready" and "waiting for the previous stage": readiness
// follows from the job's phase (§2: groups only after every tile).
enum class TaskState : int { kPending = 0, kLeased = 1, kDone = 2 };

enum class EventKind : int {
  kSubmitted = 1,
  kPhase = 2,
  kTaskLeased = 3,
  kTaskDone = 4,
  kTaskFailed = 5,
  kLeaseExpired = 6,
  kWorkerExcluded = 7,
  kProgress = 8,  // live only, never stored
  kResumed = 9,
};

// What the planning callback returns for a request (coordinator/service/job_planner.h
// is the real planner). Not core/bake/job_plan.h's JobPlan, which describes the
// tiles and groups themselves: both live in namespace wavebake and meet in
// the planner and in wb_cli.
struct PlannedJob {
  int tiles = 0;
  int groups = 0;
  int64_t total_rays_estimate = 0;
  std::string store_path{};  // relative to the store root; empty = the request's output_name
};
using PlanFn = std::function<absl::StatusOr<PlannedJob>(const v1::BakeRequest&)>;

struct JobRecord {
  int64_t id = 0;
  std::string request{};  // serialized v1::BakeRequest, defaults filled in
  Phase phase = Phase::kQueued;
  int tiles = 0, groups = 0;
  int64_t rays_estimate = 0;
  std::string store_path{};
  int max_attempts = 3;
  std::string error{};
  std::string stats_json{};
  int64_t rays_traced = 0;    // of done tasks
  int64_t bytes_written = 0;  // of done tasks
  int64_t created_ms = 0, started_ms = 0, finished_ms = 0;
  bool cleaned = false;  // cleanup callback ran (FAILED / CANCELLED jobs)

  // Tiles, groups, FINALIZE's shards and its last task (core/bake/finalize_shards.h).
  int tasks_total() const { return tiles + groups + FinalizeTasks(groups); }
  int finalize_last() const { return tasks_total() - 1; }  // its task index
};

// Called once a job has FAILED or been CANCELLED and none of its leases is
// outstanding any more, to remove its staging / partial store (§4: "nothing
// half-written is left behind"). Runs outside the coordinator's locks.
using CleanupFn = std::function<void(const JobRecord&)>;

// Task `index` of a job: tiles 0..T-1, then groups T..T+G-1, then FINALIZE's
// shards (kind_index 0..K-1) and its last task (kind_index K).
struct TaskRecord {
  int64_t job_id = 0;
  int index = 0;
  TaskKind kind = TaskKind::kBakeTile;
  int kind_index = 0;  // tile, group or FINALIZE task number
  TaskState state = TaskState::kPending;
  int attempts = 0;  // leases granted so far; the lease id carries it
  int failures = 0;  // Fail calls + lease expiries (both count toward max_attempts)
  std::string worker_id{};
  std::string last_error{};
  int64_t rays_traced = 0, bytes_written = 0;
  std::string stats_json{};
};

struct EventRecord {
  int64_t job_id = 0;
  int64_t seq = 0;
  int64_t unix_ms = 0;
  EventKind kind = EventKind::kSubmitted;
  Phase phase = Phase::kQueued;
  TaskKind task_kind = TaskKind::kBakeTile;
  int task_index = -1;  // -1: not a task event
  std::string worker_id{};
  std::string message{};
  int tasks_done = 0, tasks_total = 0;
  int64_t rays_traced = 0, bytes_written = 0;
  std::string stats_json{};
};

struct WorkerRecord {
  int64_t id = 0;
  std::string name{};
  int threads = 1;
  int64_t registered_ms = 0;
  int consecutive_failures = 0;
  bool excluded = false;
};

struct SceneRecord {
  std::string sha256{};
  int64_t size = 0;
  std::string file_name{};
  int64_t created_ms = 0;
};

}  // namespace wavebake
