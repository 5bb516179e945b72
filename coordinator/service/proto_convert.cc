#include "coordinator/service/proto_convert.h"

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace wavebake {

// The plain enums of job_types.h are stored in SQLite with the proto numbers.
static_assert(static_cast<int>(Phase::kQueued) == v1::PHASE_QUEUED);
static_assert(static_cast<int>(Phase::kCancelled) == v1::PHASE_CANCELLED);
static_assert(static_cast<int>(TaskKind::kBakeTile) == v1::BAKE_TILE);
static_assert(static_cast<int>(TaskKind::kFinalize) == v1::FINALIZE);
static_assert(static_cast<int>(EventKind::kSubmitted) == v1::EVENT_SUBMITTED);
static_assert(static_cast<int>(EventKind::kProgress) == v1::EVENT_PROGRESS);
static_assert(static_cast<int>(EventKind::kResumed) == v1::EVENT_RESUMED);

grpc::Status ToGrpc(const absl::Status& status) {
  if (status.ok()) return grpc::Status::OK;
  // absl and gRPC share the canonical code numbers.
  const auto code = static_cast<grpc::StatusCode>(status.code());
  std::string message(status.message());
  // Payloads (coordinator/service/worker_errors.h) travel as the rich error model's
  // details: type URL and serialized message, as a google.protobuf.Any.
  v1::StatusDetails details;
  status.ForEachPayload([&](absl::string_view type_url, const absl::Cord& value) {
    google::protobuf::Any* any = details.add_details();
    any->set_type_url(std::string(type_url));
    any->set_value(std::string(value));
  });
  if (details.details_size() == 0) return {code, message};
  details.set_code(static_cast<int32_t>(code));
  details.set_message(message);
  return {code, message, details.SerializeAsString()};
}

void ToProto(const JobInfo& info, v1::Job* job) {
  const JobRecord& r = info.record;
  job->Clear();
  job->set_id(absl::StrCat(r.id));
  job->mutable_request()->ParseFromString(r.request);
  job->set_phase(static_cast<v1::Phase>(r.phase));
  job->set_store_path(r.store_path);
  job->set_tiles(r.tiles);
  job->set_groups(r.groups);
  job->set_tasks_done(info.tasks_done);
  job->set_tasks_total(r.tasks_total());
  job->set_rays_traced(info.rays_traced);
  job->set_rays_estimate(info.rays_estimate);
  job->set_rays_per_second(info.rays_per_second);
  job->set_bytes_written(info.bytes_written);
  job->set_eta_seconds(info.eta_seconds);
  job->set_error(r.error);
  job->set_stats_json(r.stats_json);
  job->set_created_ms(r.created_ms);
  job->set_started_ms(r.started_ms);
  job->set_finished_ms(r.finished_ms);
  job->set_leased_tasks(info.leased_tasks);
}

namespace {

// The tasks of one phase done and in all, out of the job's `done` (tasks run
// phase after phase: tiles, then groups, then FINALIZE).
void SetPhaseTasks(const JobRecord& job, v1::JobEvent* out) {
  const int done = out->tasks_done();
  int before = 0, total = job.tasks_total();
  switch (out->phase()) {
    case v1::PHASE_BAKING:
      total = job.tiles;
      break;
    case v1::PHASE_TRANSFORMING:
      before = job.tiles;
      total = job.groups;
      break;
    case v1::PHASE_FINALIZING:
      before = job.tiles + job.groups;
      total = FinalizeTasks(job.groups);
      break;
    default:  // queued or ended: the whole job
      break;
  }
  out->set_phase_tasks_done(std::clamp(done - before, 0, total));
  out->set_phase_tasks_total(total);
}

}  // namespace

void ToProto(const EventRecord& e, const JobRecord& job, v1::JobEvent* out) {
  out->Clear();
  out->set_job_id(absl::StrCat(e.job_id));
  out->set_seq(e.seq);
  out->set_unix_ms(e.unix_ms);
  out->set_kind(static_cast<v1::EventKind>(e.kind));
  out->set_phase(static_cast<v1::Phase>(e.phase));
  if (e.task_index >= 0) {
    out->set_task_kind(static_cast<v1::TaskKind>(e.task_kind));
    out->set_task_index(e.task_index);
  }
  out->set_worker_id(e.worker_id);
  out->set_message(e.message);
  out->set_tasks_done(e.tasks_done);
  out->set_tasks_total(e.tasks_total);
  out->set_rays_traced(e.rays_traced);
  out->set_bytes_written(e.bytes_written);
  // Persisted events carry no estimate, except that a finished job has none left.
  out->set_eta_seconds(e.phase == Phase::kDone ? 0 : -1);
  out->set_stats_json(e.stats_json);
  SetPhaseTasks(job, out);
}

void ProgressEvent(const JobInfo& info, int64_t last_seq, int64_t now_ms, v1::JobEvent* out) {
  const JobRecord& r = info.record;
  out->Clear();
  out->set_job_id(absl::StrCat(r.id));
  out->set_seq(last_seq);
  out->set_unix_ms(now_ms);
  out->set_kind(v1::EVENT_PROGRESS);
  out->set_phase(static_cast<v1::Phase>(r.phase));
  out->set_tasks_done(info.tasks_done);
  out->set_tasks_total(r.tasks_total());
  out->set_rays_traced(info.rays_traced);
  out->set_rays_per_second(info.rays_per_second);
  out->set_bytes_written(info.bytes_written);
  out->set_eta_seconds(info.eta_seconds);
  SetPhaseTasks(r, out);
}

bool ToProto(const LeaseGrant& g, v1::Task* task) {
  task->Clear();
  task->set_job_id(absl::StrCat(g.key.job_id));
  task->set_kind(static_cast<v1::TaskKind>(g.kind));
  task->set_index(g.kind_index);
  task->set_store_path(g.store_path);
  task->set_lease_id(g.lease_id);
  task->set_lease_deadline_ms(g.deadline_ms);
  task->set_attempt(g.key.attempt);
  task->set_tiles(g.tiles);
  task->set_groups(g.groups);
  return task->mutable_request()->ParseFromString(g.request);
}

}  // namespace wavebake
