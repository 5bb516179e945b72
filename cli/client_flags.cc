#include "cli/client_flags.h"

#include "cli/command_error.h"

namespace wavebake::cli {

void AddClientFlags(CLI::App& cmd, driver::ClientConfig& config) {
  cmd.add_option("--coordinator", config.coordinator, "coordinator address host:port")->required();
  cmd.add_option("--token-file", config.token_file,
                 "file holding the coordinator's bearer token (first line)");
  cmd.add_option("--tls-ca", config.tls_ca, "PEM CA certificates: connect with TLS, trusting them");
}

driver::Client ConnectOrFail(const driver::ClientConfig& config, const char* command,
                             double connect_seconds) {
  absl::StatusOr<driver::Client> client = driver::Client::Connect(config, connect_seconds);
  if (!client.ok()) Fail(command, client.status());
  return *std::move(client);
}

std::string TokenOrFail(const std::string& token_file, const char* command) {
  if (token_file.empty()) return "";
  absl::StatusOr<std::string> token = driver::ReadTokenFile(token_file);
  if (!token.ok()) Fail(command, token.status());
  return *token;
}

}  // namespace wavebake::cli
