// JobService unary methods; the streaming ones are in job_service_streams.cc.
#include "coordinator/service/job_service.h"

#include <set>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "coordinator/scheduling/lease_id.h"
#include "coordinator/service/proto_convert.h"
#include "coordinator/service/update_job.h"
#include "proto/bake_request.h"
#include "storage/scene_files/scene_bundle.h"

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
    if (absl::Status s = CheckUploaded(*r.mutable_scene()->mutable_uploaded()); !s.ok())
      return Reply(s);
  }
  if (absl::Status s = ResolveUpdateJob(*deps_.table, deps_.store_root, r); !s.ok())
    return Reply(s);
  absl::StatusOr<JobInfo> info = PlanAndAdd(std::move(r));
  if (!info.ok()) return Reply(info.status());
  ToClient(*info, reply);
  return grpc::Status::OK;
}

// §4: an unknown file is bad input, named by its field. Fills in the sizes.
absl::Status JobServiceImpl::CheckUploaded(v1::SceneRef& ref) const {
  const auto known = [&](const std::string& sha,
                         const std::string& field) -> absl::StatusOr<SceneRecord> {
    if (sha.size() != 64 || sha.find_first_not_of("0123456789abcdef") != sha.npos)
      return absl::InvalidArgumentError(absl::StrCat(field, ": not 64 lowercase hex digits"));
    absl::StatusOr<std::optional<SceneRecord>> scene = deps_.scenes->Find(sha);
    if (!scene.ok()) return scene.status();
    if (!scene->has_value()) {
      return absl::InvalidArgumentError(
          absl::StrCat(field, ": no uploaded scene ", sha, " (UploadScene it first)"));
    }
    return **scene;
  };
  absl::StatusOr<SceneRecord> scene = known(ref.sha256(), "scene.uploaded.sha256");
  if (!scene.ok()) return scene.status();
  ref.set_size(scene->size);
  if (ref.file_name().empty()) ref.set_file_name(scene->file_name);
  if (ref.files_size() > kMaxSceneFiles) {
    return absl::InvalidArgumentError(
        absl::StrCat("scene.uploaded.files: more than ", kMaxSceneFiles, " files"));
  }
  std::set<std::string> paths;
  for (int i = 0; i < ref.files_size(); ++i) {
    v1::SceneFileRef& f = *ref.mutable_files(i);
    const std::string field = absl::StrCat("scene.uploaded.files[", i, "]");
    if (absl::Status s = CheckBundlePath(f.path(), field + ".path"); !s.ok()) return s;
    if (!paths.insert(f.path()).second) {
      return absl::InvalidArgumentError(absl::StrCat(field, ".path: '", f.path(), "' twice"));
    }
    absl::StatusOr<SceneRecord> file = known(f.sha256(), field + ".sha256");
    if (!file.ok()) return file.status();
    f.set_size(file->size);
  }
  return absl::OkStatus();
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
