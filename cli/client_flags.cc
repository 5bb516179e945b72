#include "cli/client_flags.h"

namespace wavebake::cli {

void AddClientFlags(CLI::App& cmd, driver::ClientConfig& config) {
  cmd.add_option("--coordinator", config.coordinator, "coordinator address host:port")->required();
  cmd.add_option("--token-file", config.token_file,
                 "file holding the coordinator's bearer token (first line)");
  cmd.add_option("--tls-ca", config.tls_ca, "PEM CA certificates: connect with TLS, trusting them");
}

}  // namespace wavebake::cli
