// JobService unary methods; the streaming ones are in job_service_streams.cc.
#include "coordinator/job_service.h"

#include <system_error>

#include "absl/strings/str_cat.h"
#include "coordinator/lease_id.h"
#include "coordinator/proto_convert.h"
#include "proto/bake_request.h"

namespace wavebake {

absl::StatusOr<int64_t> ParseJobId(const v1::JobId& id) {
  std::optional<int64_t> v = ParseId(id.id());
  if (!v) return absl::InvalidArgumentError(absl::StrCat("id: \"", id.id(), "\" is not a job id"));
  return *v;
}

grpc::Status JobServiceImpl::Reply(const absl::Status& status) const {
  return ToGrpc(absl::Status(status.code(), deps_.client_paths(std::string(status.message()))));
}

void JobServiceImpl::ToClient(const JobInfo& info, v1::Job* job) const {
  ToProto(info, job);
  job->set_error(deps_.client_paths(job->error()));
}

grpc::Status JobServiceImpl::Submit(grpc::ServerContext* context, const v1::BakeRequest* request,
                                    v1::Job* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  v1::BakeRequest r = *request;
  if (absl::Status s = NormalizeBakeRequest(r); !s.ok()) return Reply(s);
  if (r.scene().has_uploaded()) {
    // §4: an unknown file is bad input, named by its field.
    v1::SceneRef& ref = *r.mutable_scene()->mutable_uploaded();
    absl::StatusOr<std::optional<SceneRecord>> scene = deps_.scenes->Find(ref.sha256());
    if (!scene.ok()) return Reply(scene.status());
    if (!scene->has_value()) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              absl::StrCat("scene.uploaded.sha256: no uploaded scene ", ref.sha256(),
                           " (UploadScene it first)")};
    }
    ref.set_size((*scene)->size);
    if (ref.file_name().empty()) ref.set_file_name((*scene)->file_name);
  }
  absl::StatusOr<JobInfo> info = PlanAndAdd(std::move(r));
  if (!info.ok()) return Reply(info.status());
  ToClient(*info, reply);
  return grpc::Status::OK;
}

// The planner may load the scene and take a while: it runs with no lock held,
// between reserving the job id (which names the default store) and adding the job.
absl::StatusOr<JobInfo> JobServiceImpl::PlanAndAdd(v1::BakeRequest request) {
  const int64_t id = deps_.table->ReserveJobId();
  if (request.output_name().empty()) request.set_output_name(absl::StrCat("job-", id, ".wbk"));
  // Never bake over an existing store: a failed or cancelled job's cleanup
  // would delete it.
  std::error_code ec;
  if (std::filesystem::exists(deps_.store_root / request.output_name(), ec)) {
    return absl::AlreadyExistsError(absl::StrCat("output_name: \"", request.output_name(),
                                                 "\" already exists in the store root"));
  }
  absl::StatusOr<PlannedJob> plan = deps_.plan(request);
  if (!plan.ok()) return plan.status();
  if (plan->store_path.empty()) plan->store_path = request.output_name();
  std::string bytes;
  request.SerializeToString(&bytes);
  return deps_.table->AddJob(id, std::move(bytes), request.max_attempts(), *plan);
}

grpc::Status JobServiceImpl::Get(grpc::ServerContext* context, const v1::JobId* request,
                                 v1::Job* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> id = ParseJobId(*request);
  if (!id.ok()) return Reply(id.status());
  absl::StatusOr<JobInfo> info = deps_.table->Get(*id);
  if (!info.ok()) return Reply(info.status());
  ToClient(*info, reply);
  return grpc::Status::OK;
}

grpc::Status JobServiceImpl::List(grpc::ServerContext* context, const v1::ListRequest* request,
                                  v1::JobList* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  if (request->limit() < 0) {
    return {grpc::StatusCode::INVALID_ARGUMENT,
            absl::StrCat("limit: ", request->limit(), " is negative")};
  }
  const int limit = request->limit() == 0 ? 100 : request->limit();
  for (const JobInfo& info : deps_.table->List(limit, request->active_only())) {
    ToClient(info, reply->add_jobs());
  }
  return grpc::Status::OK;
}

grpc::Status JobServiceImpl::Cancel(grpc::ServerContext* context, const v1::JobId* request,
                                    v1::Job* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> id = ParseJobId(*request);
  if (!id.ok()) return Reply(id.status());
  absl::StatusOr<JobInfo> info = deps_.table->Cancel(*id);
  if (!info.ok()) return Reply(info.status());
  ToClient(*info, reply);
  return grpc::Status::OK;
}

}  // namespace wavebake
