#include "driver/jobs/job_query.h"

#include "absl/strings/str_cat.h"

namespace wavebake::driver {
namespace {

v1::JobId ToId(const std::string& job_id) {
  v1::JobId id;
  id.set_id(job_id);
  return id;
}

}  // namespace

absl::StatusOr<v1::Job> GetJob(const Client& client, const std::string& job_id) {
  v1::Job job;
  if (grpc::Status s = client.jobs().Get(client.Call().get(), ToId(job_id), &job); !s.ok())
    return FromGrpc(s);
  return job;
}

absl::StatusOr<std::vector<v1::Job>> ListJobs(const Client& client, int limit, bool active_only) {
  v1::ListRequest request;
  request.set_limit(limit);
  request.set_active_only(active_only);
  v1::JobList list;
  if (grpc::Status s = client.jobs().List(client.Call().get(), request, &list); !s.ok())
    return FromGrpc(s);
  return std::vector<v1::Job>(list.jobs().begin(), list.jobs().end());
}

absl::StatusOr<v1::Job> CancelJob(const Client& client, const std::string& job_id) {
  v1::Job job;
  if (grpc::Status s = client.jobs().Cancel(client.Call().get(), ToId(job_id), &job); !s.ok())
    return FromGrpc(s);
  return job;
}

std::string JobOutcome(const v1::Job& job) {
  // PHASE_DONE -> "DONE".
  std::string text = absl::StrCat("job ", job.id(), " ", v1::Phase_Name(job.phase()).substr(6));
  if (!job.error().empty()) absl::StrAppend(&text, ": ", job.error());
  if (job.phase() == v1::PHASE_DONE) absl::StrAppend(&text, " (store ", job.store_path(), ")");
  return text;
}

}  // namespace wavebake::driver
