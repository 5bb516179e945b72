#include "driver/jobs/health.h"

#include "absl/strings/str_cat.h"
#include "health.grpc.pb.h"

namespace wavebake::driver {

absl::Status CheckHealth(const Client& client, const std::string& address,
                         const std::string& service, int64_t timeout_ms) {
  auto stub = grpc::health::v1::Health::NewStub(client.channel());
  grpc::health::v1::HealthCheckRequest request;
  request.set_service(service);
  grpc::health::v1::HealthCheckResponse reply;
  const grpc::Status s = stub->Check(client.Call(timeout_ms).get(), request, &reply);
  if (!s.ok()) {
    return absl::UnavailableError(
        absl::StrCat("--coordinator ", address, ": health check: ", FromGrpc(s).message()));
  }
  if (reply.status() != grpc::health::v1::HealthCheckResponse::SERVING) {
    return absl::UnavailableError(
        absl::StrCat("--coordinator ", address, ": ",
                     grpc::health::v1::HealthCheckResponse::ServingStatus_Name(reply.status())));
  }
  return absl::OkStatus();
}

}  // namespace wavebake::driver
