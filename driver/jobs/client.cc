#include "driver/jobs/client.h"

#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>

#include <fstream>
#include <sstream>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"

namespace wavebake::driver {

absl::Status FromGrpc(const grpc::Status& status) {
  return absl::Status(static_cast<absl::StatusCode>(status.error_code()), status.error_message());
}

absl::StatusOr<std::string> ReadTextFile(const std::string& path, const std::string& flag) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (!(in && text << in.rdbuf()))
    return absl::InvalidArgumentError(absl::StrCat(flag, ": cannot read '", path, "'"));
  return text.str();
}

absl::StatusOr<std::string> ReadTokenFile(const std::string& path) {
  absl::StatusOr<std::string> text = ReadTextFile(path, "token_file");
  if (!text.ok()) return text.status();
  std::string token = text->substr(0, text->find('\n'));
  absl::StripAsciiWhitespace(&token);
  if (token.empty())
    return absl::InvalidArgumentError(absl::StrCat("token_file: '", path, "' holds no token"));
  return token;
}

absl::StatusOr<Client> Client::Connect(const ClientConfig& config, double connect_seconds) {
  std::string token;
  if (!config.token_file.empty()) {
    absl::StatusOr<std::string> t = ReadTokenFile(config.token_file);
    if (!t.ok()) return t.status();
    token = *t;
  }
  std::shared_ptr<grpc::ChannelCredentials> creds = grpc::InsecureChannelCredentials();
  if (!config.tls_ca.empty()) {
    absl::StatusOr<std::string> roots = ReadTextFile(config.tls_ca, "tls_ca");
    if (!roots.ok()) return roots.status();
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = *roots;
    creds = grpc::SslCredentials(ssl);
  }
  // Stores and scenes travel in 1 MiB chunks; leave room for the envelope.
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(16 << 20);
  args.SetMaxSendMessageSize(16 << 20);
  // A coordinator that restarts is back within seconds: retry that soon,
  // not after gRPC's default backoff of up to two minutes.
  args.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 200);
  args.SetInt(GRPC_ARG_MIN_RECONNECT_BACKOFF_MS, 200);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 2000);
  std::shared_ptr<grpc::Channel> channel =
      grpc::CreateCustomChannel(config.coordinator, creds, args);
  if (connect_seconds > 0 &&
      !channel->WaitForConnected(
          std::chrono::system_clock::now() +
          std::chrono::milliseconds(static_cast<int64_t>(connect_seconds * 1000)))) {
    return absl::UnavailableError(absl::StrCat("coordinator: cannot connect to ",
                                               config.coordinator, " within ", connect_seconds,
                                               " s (is it running? does it serve TLS: --tls-ca?)"));
  }
  return Client(std::move(channel), std::move(token));
}

Client::Client(std::shared_ptr<grpc::Channel> channel, std::string token)
    : channel_(std::move(channel)),
      token_(std::move(token)),
      jobs_(v1::JobService::NewStub(channel_)) {}

std::unique_ptr<grpc::ClientContext> Client::Call(int64_t timeout_ms) const {
  auto ctx = std::make_unique<grpc::ClientContext>();
  if (timeout_ms > 0)
    ctx->set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(timeout_ms));
  if (!token_.empty()) ctx->AddMetadata("authorization", "Bearer " + token_);
  return ctx;
}

}  // namespace wavebake::driver
