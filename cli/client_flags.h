#pragma once
// The flags every client of a running coordinator takes (`submit`, `watch`,
// `status`, `cancel`, `fetch`, `worker`): --coordinator, --token-file, --tls-ca.
#include <CLI/CLI.hpp>

#include "driver/jobs/client.h"

namespace wavebake::cli {

void AddClientFlags(CLI::App& cmd, driver::ClientConfig& config);

// The client of --coordinator; one that cannot connect fails `command`.
driver::Client ConnectOrFail(const driver::ClientConfig& config, const char* command,
                             double connect_seconds = 5);

// The token in a --token-file ("" for no file); an unreadable file fails `command`.
std::string TokenOrFail(const std::string& token_file, const char* command);

}  // namespace wavebake::cli
