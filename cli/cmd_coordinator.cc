// `wavebake coordinator --listen ADDR --data DIR [--http ADDR]` (DESIGN.md
// §4, §5): the coordinator process (driver/process/coordinator_run.h), and with
// --http the web monitor and /metrics, until SIGINT or SIGTERM.
#include <spdlog/spdlog.h>

#include <chrono>
#include <future>
#include <memory>
#include <mutex>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/web_flags.h"
#include "driver/process/coordinator_run.h"
#include "driver/process/exit_deadline.h"
#include "driver/process/signal_watcher.h"
#include "web/coordinator_source.h"

namespace wavebake::cli {
namespace {

struct CoordinatorFlags {
  CoordinatorOptions options{.listen_address = "", .wait_ms = 100};
  std::string token_file, address_file;
  int64_t max_upload_mb = 1024;
  int64_t test_plan_delay_ms = 0;
  WebFlags web;
};

// Shutdown gives running calls 2 s (Coordinator::Shutdown), then this.
constexpr std::chrono::milliseconds kShutdownBound{5000};

void Run(CoordinatorFlags f) {
  spdlog::set_level(spdlog::level::info);  // its log is its output
  std::promise<void> stop;
  driver::SignalWatcher signals([&, once = std::make_shared<std::once_flag>()](int) {
    std::call_once(*once, [&] { stop.set_value(); });
  });
  CoordinatorOptions& options = f.options;
  options.max_upload_bytes = f.max_upload_mb << 20;
  options.token = TokenOrFail(f.token_file, "coordinator");
  absl::StatusOr<driver::CoordinatorRun> run =
      driver::StartCoordinator(options, f.address_file, f.test_plan_delay_ms);
  if (!run.ok()) Fail("coordinator", run.status());
  Coordinator& coordinator = *run->coordinator;
  // The same token and certificate as gRPC (DESIGN.md §4).
  f.web.options.token = options.token;
  f.web.options.tls_cert = options.tls_cert_path, f.web.options.tls_key = options.tls_key_path;
  std::unique_ptr<web::MonitorServer> monitor =
      StartMonitor("coordinator", f.web, web::CoordinatorSource(coordinator, run->planner));
  stop.get_future().wait();
  spdlog::info("coordinator: shutting down");
  // Bounded (driver/process/exit_deadline.h): a call stuck in a long planning step
  // must not keep a stopped coordinator alive.
  driver::ExitDeadline deadline(kShutdownBound, "coordinator", 1);
  if (monitor) monitor->Stop();  // it reads the coordinator
  coordinator.Shutdown();
  run->coordinator.reset();  // its server's threads end here, still within the bound
}

}  // namespace

void AddCoordinatorCommand(CLI::App& app) {
  auto f = std::make_shared<CoordinatorFlags>();
  CLI::App* cmd = app.add_subcommand(
      "coordinator",
      "run the coordinator: clients submit and watch jobs, workers lease their tasks "
      "(until SIGINT/SIGTERM)");
  CoordinatorOptions& o = f->options;
  cmd->add_option("--listen", o.listen_address,
                  "address to serve gRPC on, host:port (port 0: any free)")
      ->required();
  cmd->add_option("--data", o.data_dir,
                  "directory of the job state (SQLite), uploaded scenes and, "
                  "by default, the store root")
      ->required();
  cmd->add_option("--store-root", o.store_root,
                  "where stores are built, shared with the workers (default DATA/store)");
  cmd->add_option("--token-file", f->token_file,
                  "require this bearer token (first line of the file) on every RPC");
  cmd->add_option("--tls-cert", o.tls_cert_path, "PEM certificate: serve TLS (with --tls-key)");
  cmd->add_option("--tls-key", o.tls_key_path, "PEM private key of --tls-cert");
  cmd->add_option("--health-listen", o.health_address,
                  "also serve the gRPC health service alone, in plain text, on host:port "
                  "(for Kubernetes' grpc probes, which speak no TLS)");
  cmd->add_option("--lease-seconds", o.lease_seconds,
                  "how long a task's lease lasts without a heartbeat")
      ->capture_default_str();
  cmd->add_option("--lease-wait-ms", o.wait_ms,
                  "how long an idle worker waits before asking for work again")
      ->capture_default_str();
  cmd->add_option("--max-upload-mb", f->max_upload_mb, "largest scene upload accepted")
      ->capture_default_str();
  cmd->add_option("--worker-failure-limit", o.worker_failure_limit,
                  "consecutive task failures that exclude a worker")
      ->capture_default_str();
  cmd->add_option("--address-file", f->address_file,
                  "write the address it listens on (host:port) to this file once serving");
  // Hidden (no group): a test hook, not an option for users.
  cmd->add_option("--test-plan-delay-ms", f->test_plan_delay_ms,
                  "tests only: every plan sleeps this long first")
      ->group("");
  AddWebFlags(*cmd, f->web, "--http",
              "also serve the web monitor, /metrics and /healthz over HTTP on host:port "
              "(HTTPS with --tls-cert; the same --token-file)");
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
