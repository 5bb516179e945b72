#include "coordinator/service/worker_service.h"

#include <fstream>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "coordinator/scheduling/lease_id.h"
#include "coordinator/service/proto_convert.h"
#include "coordinator/service/worker_paths.h"

namespace wavebake {
namespace {

constexpr size_t kMaxReasonBytes = 4096;
constexpr size_t kMaxStatsBytes = 1 << 20;

grpc::Status BadField(absl::string_view field, absl::string_view why) {
  return {grpc::StatusCode::INVALID_ARGUMENT, absl::StrCat(field, ": ", why)};
}

absl::StatusOr<int64_t> ParseWorkerId(const std::string& id) {
  std::optional<int64_t> v = ParseId(id);
  if (!v)
    return absl::InvalidArgumentError(absl::StrCat("worker_id: \"", id, "\" is not a worker id"));
  return *v;
}

absl::StatusOr<LeaseKey> ParseLease(absl::string_view field, const std::string& id) {
  std::optional<LeaseKey> key = ParseLeaseId(id);
  if (!key)
    return absl::InvalidArgumentError(absl::StrCat(field, ": \"", id, "\" is not a lease id"));
  return *key;
}

// A task result as Complete and LeaseBatch take it; errors name `field`.
absl::StatusOr<Completion> ParseResult(const std::string& field, const v1::TaskResult& r) {
  absl::StatusOr<LeaseKey> key = ParseLease(field + "lease_id", r.lease_id());
  if (!key.ok()) return key.status();
  const auto bad = [&](absl::string_view name, absl::string_view why) {
    return absl::InvalidArgumentError(absl::StrCat(field, name, ": ", why));
  };
  if (r.rays_traced() < 0) return bad("rays_traced", "negative");
  if (r.bytes_written() < 0) return bad("bytes_written", "negative");
  if (r.stats_json().size() > kMaxStatsBytes) return bad("stats_json", "longer than 1 MiB");
  return Completion{*key, {r.rays_traced(), r.bytes_written(), r.stats_json()}};
}

constexpr int kMaxBatch = 4096;  // = the most threads a worker may register

}  // namespace

grpc::Status WorkerServiceImpl::Register(grpc::ServerContext* context,
                                         const v1::WorkerInfo* request, v1::WorkerId* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  if (request->threads() < 1 || request->threads() > 4096) {
    return BadField("threads", absl::StrCat(request->threads(), " is not in 1..4096"));
  }
  if (request->name().size() > 256) return BadField("name", "longer than 256 bytes");
  absl::StatusOr<int64_t> id = deps_.table->RegisterWorker(request->name(), request->threads());
  if (!id.ok()) return ToGrpc(id.status());
  reply->set_id(absl::StrCat(*id));
  reply->set_store_root_id(deps_.store_root_id);
  return grpc::Status::OK;
}

grpc::Status WorkerServiceImpl::Lease(grpc::ServerContext* context, const v1::LeaseRequest* request,
                                      v1::LeaseReply* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> worker = ParseWorkerId(request->worker_id());
  if (!worker.ok()) return ToGrpc(worker.status());
  absl::StatusOr<std::optional<LeaseGrant>> grant = deps_.table->Lease(*worker);
  if (!grant.ok()) return ToGrpc(grant.status());
  if (!grant->has_value()) {
    reply->set_wait_ms(static_cast<int32_t>(deps_.wait_ms));
    return grpc::Status::OK;
  }
  if (!ToProto(**grant, reply->mutable_task())) {
    return {grpc::StatusCode::DATA_LOSS,
            absl::StrCat("job ", (*grant)->key.job_id, ": stored request does not parse")};
  }
  return grpc::Status::OK;
}

grpc::Status WorkerServiceImpl::Heartbeat(grpc::ServerContext* context,
                                          const v1::HeartbeatRequest* request,
                                          v1::HeartbeatReply* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> worker = ParseWorkerId(request->worker_id());
  if (!worker.ok()) return ToGrpc(worker.status());
  std::vector<LeaseProgressReport> reports;
  reports.reserve(request->leases_size());
  for (int i = 0; i < request->leases_size(); ++i) {
    const v1::LeaseProgress& p = request->leases(i);
    const std::string field = absl::StrCat("leases[", i, "]");
    absl::StatusOr<LeaseKey> key = ParseLease(field + ".lease_id", p.lease_id());
    if (!key.ok()) return ToGrpc(key.status());
    if (p.rays_traced() < 0 || p.bytes_written() < 0) return BadField(field, "negative counter");
    reports.push_back({*key, p.rays_traced(), p.bytes_written()});
  }
  absl::StatusOr<HeartbeatResult> result = deps_.table->Heartbeat(*worker, reports);
  if (!result.ok()) return ToGrpc(result.status());
  for (const LeaseKey& k : result->renewed) reply->add_renewed_lease_ids(FormatLeaseId(k));
  for (const LeaseKey& k : result->cancelled) reply->add_cancelled_lease_ids(FormatLeaseId(k));
  reply->set_lease_deadline_ms(result->deadline_ms);
  return grpc::Status::OK;
}

grpc::Status WorkerServiceImpl::Complete(grpc::ServerContext* context,
                                         const v1::TaskResult* request, v1::CompleteReply* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> worker = ParseWorkerId(request->worker_id());
  if (!worker.ok()) return ToGrpc(worker.status());
  absl::StatusOr<Completion> done = ParseResult("", *request);
  if (!done.ok()) return ToGrpc(done.status());
  absl::StatusOr<bool> accepted = deps_.table->Complete(*worker, done->key, done->report);
  if (!accepted.ok()) return ToGrpc(accepted.status());
  reply->set_accepted(*accepted);
  return grpc::Status::OK;
}

grpc::Status WorkerServiceImpl::LeaseBatch(grpc::ServerContext* context,
                                           const v1::LeaseBatchRequest* request,
                                           v1::LeaseBatchReply* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> worker = ParseWorkerId(request->worker_id());
  if (!worker.ok()) return ToGrpc(worker.status());
  if (request->max_tasks() < 0 || request->max_tasks() > kMaxBatch) {
    return BadField("max_tasks", absl::StrCat(request->max_tasks(), " is not in 0..", kMaxBatch));
  }
  if (request->completed_size() > kMaxBatch) {
    return BadField("completed", absl::StrCat("more than ", kMaxBatch, " results"));
  }
  std::vector<Completion> done;
  done.reserve(request->completed_size());
  for (int i = 0; i < request->completed_size(); ++i) {
    const v1::TaskResult& r = request->completed(i);
    const std::string field = absl::StrCat("completed[", i, "].");
    if (!r.worker_id().empty() && r.worker_id() != request->worker_id()) {
      return BadField(field + "worker_id", "is not the request's worker_id");
    }
    absl::StatusOr<Completion> c = ParseResult(field, r);
    if (!c.ok()) return ToGrpc(c.status());
    done.push_back(std::move(*c));
  }
  absl::StatusOr<ExchangeResult> result =
      deps_.table->Exchange(*worker, done, request->max_tasks());
  if (!result.ok()) return ToGrpc(result.status());
  for (bool accepted : result->accepted) reply->add_accepted(accepted);
  for (const LeaseGrant& grant : result->grants) {
    if (!ToProto(grant, reply->add_tasks())) {
      return {grpc::StatusCode::DATA_LOSS,
              absl::StrCat("job ", grant.key.job_id, ": stored request does not parse")};
    }
  }
  if (reply->tasks_size() < request->max_tasks()) {
    reply->set_wait_ms(static_cast<int32_t>(deps_.wait_ms));
  }
  return grpc::Status::OK;
}

grpc::Status WorkerServiceImpl::Fail(grpc::ServerContext* context, const v1::TaskFailure* request,
                                     v1::FailReply* reply) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  absl::StatusOr<int64_t> worker = ParseWorkerId(request->worker_id());
  if (!worker.ok()) return ToGrpc(worker.status());
  absl::StatusOr<LeaseKey> key = ParseLease("lease_id", request->lease_id());
  if (!key.ok()) return ToGrpc(key.status());
  std::string reason = request->reason().substr(0, kMaxReasonBytes);
  if (reason.empty()) reason = "no reason given";
  if (deps_.hide_worker_paths) {
    absl::StatusOr<JobInfo> job = deps_.table->Get(key->job_id);
    reason = HideWorkerPaths(reason, job.ok() ? job->record.store_path : std::string());
  }
  absl::StatusOr<bool> counted = deps_.table->Fail(
      *worker, *key, reason,
      request->permanent() ? LeaseTable::Failure::kPermanent : LeaseTable::Failure::kTransient);
  if (!counted.ok()) return ToGrpc(counted.status());
  reply->set_accepted(*counted);
  return grpc::Status::OK;
}

grpc::Status WorkerServiceImpl::FetchScene(grpc::ServerContext* context,
                                           const v1::SceneRef* request,
                                           grpc::ServerWriter<v1::SceneChunk>* writer) {
  if (grpc::Status s = deps_.auth->Check(*context); !s.ok()) return s;
  const std::string& sha = request->sha256();
  if (sha.size() != 64 || sha.find_first_not_of("0123456789abcdef") != sha.npos) {
    return BadField("sha256", "must be 64 lowercase hex digits");
  }
  absl::StatusOr<std::optional<SceneRecord>> rec = deps_.scenes->Find(sha);
  if (!rec.ok()) return ToGrpc(rec.status());
  if (!rec->has_value())
    return {grpc::StatusCode::NOT_FOUND, absl::StrCat("sha256: no scene ", sha)};
  std::ifstream in(deps_.scenes->BlobPath(sha), std::ios::binary);
  if (!in) return {grpc::StatusCode::INTERNAL, absl::StrCat("cannot read scene ", sha)};
  std::string buffer(static_cast<size_t>(deps_.chunk_bytes), '\0');
  v1::SceneChunk chunk;
  chunk.set_sha256(sha);
  chunk.set_size((*rec)->size);
  chunk.set_file_name((*rec)->file_name);
  int64_t offset = 0;
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const int64_t n = in.gcount();
    if (n == 0) break;
    chunk.set_offset(offset);
    chunk.set_data(buffer.data(), static_cast<size_t>(n));
    if (context->IsCancelled() || !writer->Write(chunk)) return grpc::Status::OK;
    offset += n;
    chunk.clear_sha256();  // only the first chunk names the scene
    chunk.clear_size();
    chunk.clear_file_name();
  }
  return grpc::Status::OK;
}

}  // namespace wavebake
