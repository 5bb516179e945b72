#pragma once
// Bearer-token check of every RPC (DESIGN.md §4: "Every RPC checks a bearer
// token when one is configured"). A per-method check rather than an
// interceptor: gRPC 1.51's server interceptors are experimental and cannot
// answer a call with a status. Health checking and reflection stay open so
// probes work without the secret.
#include <grpcpp/server_context.h>

#include <string>
#include <string_view>

namespace wavebake {

class TokenAuth {
 public:
  explicit TokenAuth(std::string token) : token_(std::move(token)) {}
  bool enabled() const { return !token_.empty(); }
  // OK, or UNAUTHENTICATED when the `authorization: Bearer <token>` metadata
  // is missing or wrong.
  grpc::Status Check(const grpc::ServerContext& context) const;
  // `token` is the configured token, compared in time independent of where
  // they differ (the web monitor's header and login form use it too).
  bool Matches(std::string_view token) const;

 private:
  std::string token_;
};

}  // namespace wavebake
