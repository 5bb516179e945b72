#pragma once
// wavebake.v1.WorkerService (DESIGN.md §4): workers register, pull tasks
// under leases, renew them, report results and fetch scenes by hash.
#include "coordinator/service/service_deps.h"
#include "wavebake.grpc.pb.h"

namespace wavebake {

class WorkerServiceImpl final : public v1::WorkerService::Service {
 public:
  explicit WorkerServiceImpl(ServiceDeps deps) : deps_(std::move(deps)) {}

  grpc::Status Register(grpc::ServerContext* context, const v1::WorkerInfo* request,
                        v1::WorkerId* reply) override;
  grpc::Status Lease(grpc::ServerContext* context, const v1::LeaseRequest* request,
                     v1::LeaseReply* reply) override;
  grpc::Status Heartbeat(grpc::ServerContext* context, const v1::HeartbeatRequest* request,
                         v1::HeartbeatReply* reply) override;
  grpc::Status Complete(grpc::ServerContext* context, const v1::TaskResult* request,
                        v1::CompleteReply* reply) override;
  grpc::Status Fail(grpc::ServerContext* context, const v1::TaskFailure* request,
                    v1::FailReply* reply) override;
  grpc::Status LeaseBatch(grpc::ServerContext* context, const v1::LeaseBatchRequest* request,
                          v1::LeaseBatchReply* reply) override;
  grpc::Status FetchScene(grpc::ServerContext* context, const v1::SceneRef* request,
                          grpc::ServerWriter<v1::SceneChunk>* writer) override;

 private:
  ServiceDeps deps_;
};

}  // namespace wavebake
