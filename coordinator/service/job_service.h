#pragma once
// wavebake.v1.JobService (DESIGN.md §4): clients submit, inspect, cancel and
// watch jobs, upload scenes and read finished stores.
#include "coordinator/service/service_deps.h"
#include "wavebake.grpc.pb.h"

namespace wavebake {

class JobServiceImpl final : public v1::JobService::Service {
 public:
  explicit JobServiceImpl(ServiceDeps deps) : deps_(std::move(deps)) {}

  grpc::Status Submit(grpc::ServerContext* context, const v1::BakeRequest* request,
                      v1::Job* reply) override;
  grpc::Status Get(grpc::ServerContext* context, const v1::JobId* request, v1::Job* reply) override;
  grpc::Status List(grpc::ServerContext* context, const v1::ListRequest* request,
                    v1::JobList* reply) override;
  grpc::Status Cancel(grpc::ServerContext* context, const v1::JobId* request,
                      v1::Job* reply) override;
  grpc::Status Watch(grpc::ServerContext* context, const v1::JobId* request,
                     grpc::ServerWriter<v1::JobEvent>* writer) override;
  grpc::Status UploadScene(grpc::ServerContext* context, grpc::ServerReader<v1::SceneChunk>* reader,
                           v1::SceneRef* reply) override;
  grpc::Status ReadStore(grpc::ServerContext* context, const v1::JobId* request,
                         grpc::ServerWriter<v1::FileChunk>* writer) override;

 private:
  absl::StatusOr<JobInfo> PlanAndAdd(v1::BakeRequest request);
  // What a client receives: messages with the server's paths hidden.
  grpc::Status Reply(const absl::Status& status) const;
  void ToClient(const JobInfo& info, v1::Job* job) const;
  absl::Status CheckUploaded(v1::SceneRef& ref) const;

  static constexpr int kMaxSceneFiles = 4096;

  ServiceDeps deps_;
};

// "42" -> 42; INVALID_ARGUMENT naming the field otherwise.
absl::StatusOr<int64_t> ParseJobId(const v1::JobId& id);

}  // namespace wavebake
