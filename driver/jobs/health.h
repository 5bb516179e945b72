#pragma once
// The coordinator's standard gRPC health (grpc.health.v1.Health/Check,
// DESIGN.md §4), for probes (deploy/k8s runs `wavebake health` as its
// readiness and liveness checks) and scripts. Needs no token.
#include <cstdint>
#include <string>

#include "absl/status/status.h"
#include "driver/jobs/client.h"

namespace wavebake::driver {

// OK when the coordinator answers SERVING for `service` ("" = the whole
// server) within timeout_ms; UNAVAILABLE naming the address and the status
// it answered otherwise.
absl::Status CheckHealth(const Client& client, const std::string& address,
                         const std::string& service, int64_t timeout_ms);

}  // namespace wavebake::driver
