// `wavebake health --coordinator ADDR` (DESIGN.md §4 standard gRPC health):
// exit 0 if the coordinator answers SERVING within --timeout. The
// readiness and liveness probe of deploy/k8s; no token needed.
#include <cstdio>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "driver/health.h"

namespace wavebake::cli {
namespace {

struct HealthFlags {
  driver::ClientConfig client;
  std::string service;
  double timeout_seconds = 5;
};

void Run(const HealthFlags& f) {
  absl::StatusOr<driver::Client> client = driver::Client::Connect(f.client, /*connect_seconds=*/0);
  if (!client.ok()) Fail("health", client.status());
  const absl::Status s = driver::CheckHealth(*client, f.client.coordinator, f.service,
                                             static_cast<int64_t>(f.timeout_seconds * 1000));
  if (!s.ok()) Fail("health", s);
  std::printf("SERVING\n");
}

}  // namespace

void AddHealthCommand(CLI::App& app) {
  auto f = std::make_shared<HealthFlags>();
  CLI::App* cmd = app.add_subcommand(
      "health", "check a coordinator's gRPC health (exit 0 if SERVING; a probe for deploy/k8s)");
  AddClientFlags(*cmd, f->client);
  cmd->add_option("--service", f->service, "health service name (default: the whole server)");
  cmd->add_option("--timeout", f->timeout_seconds, "seconds to wait for the answer")
      ->capture_default_str();
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
