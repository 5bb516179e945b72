#pragma once
// What every client of a running coordinator shares (DESIGN.md §5 `wavebake
// submit|watch|status|cancel|fetch`, `wavebake worker`, the web monitor and
// the Python module): the coordinator's address, the bearer token and TLS,
// and calls that carry them.
#include <grpcpp/channel.h>
#include <grpcpp/client_context.h>

#include <cstdint>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "wavebake.grpc.pb.h"

namespace wavebake::driver {

// Where the coordinator is and how to prove who we are. Errors about these
// name the command-line flag that sets them (--coordinator, --token-file,
// --tls-ca), which is also the field a caller from Python or the web sets.
struct ClientConfig {
  std::string coordinator{};  // host:port
  std::string token_file{};   // the bearer token, first line; empty = none
  std::string tls_ca{};       // PEM roots to trust; empty = plaintext
};

// absl and gRPC share the canonical codes; the message keeps the code's name
// (e.g. "UNAUTHENTICATED: missing bearer token").
absl::Status FromGrpc(const grpc::Status& status);

class Client {
 public:
  // A channel to the coordinator, or the error naming the bad flag (an
  // unreadable token or CA file). With connect_seconds > 0 it waits that long
  // for the coordinator to answer (one started just before may still be
  // coming up) and is UNAVAILABLE naming the address if it does not.
  static absl::StatusOr<Client> Connect(const ClientConfig& config, double connect_seconds = 5);
  // Over an existing channel, e.g. a Coordinator's InProcessChannel().
  Client(std::shared_ptr<grpc::Channel> channel, std::string token);

  // A call's context: the token, and a deadline (0 = none, for streams that
  // last as long as a job).
  std::unique_ptr<grpc::ClientContext> Call(int64_t timeout_ms = 30'000) const;
  v1::JobService::Stub& jobs() const { return *jobs_; }
  const std::shared_ptr<grpc::Channel>& channel() const { return channel_; }
  const std::string& token() const { return token_; }

 private:
  std::shared_ptr<grpc::Channel> channel_;
  std::string token_;
  std::shared_ptr<v1::JobService::Stub> jobs_;
};

// The token in a --token-file: its first line, without surrounding blanks.
// An unreadable or empty file is InvalidArgument naming the flag.
absl::StatusOr<std::string> ReadTokenFile(const std::string& path);
// A whole file (PEM certificates and keys); errors name `flag`.
absl::StatusOr<std::string> ReadTextFile(const std::string& path, const std::string& flag);

}  // namespace wavebake::driver
