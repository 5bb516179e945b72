// `wavebake worker --coordinator ADDR --store-root DIR` (DESIGN.md §4, §5):
// leases tasks and runs them until SIGTERM or SIGINT, which drains it (no new
// task; the running ones finish and are reported, then exit 0). A second
// signal stops the running tasks too (reported as failed).
#include <spdlog/spdlog.h>

#include <thread>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "driver/process/signal_watcher.h"
#include "driver/process/worker_run.h"

namespace wavebake::cli {
namespace {

struct WorkerFlags {
  driver::ClientConfig client;
  WorkerOptions options{.threads =
                            static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))};
};

void Run(const WorkerFlags& f) {
  spdlog::set_level(spdlog::level::info);  // its log is its output
  driver::WorkerRun run;
  driver::SignalWatcher signals([&](int) { run.Stop(); });
  // No waiting here: the loop registers as soon as the coordinator is up.
  const driver::Client client = ConnectOrFail(f.client, "worker", 0);
  WorkerOptions options = f.options;
  options.token = client.token();
  const absl::Status status = run.Run(client.channel(), std::move(options));
  if (!status.ok()) Fail("worker", status);
}

}  // namespace

void AddWorkerCommand(CLI::App& app) {
  auto f = std::make_shared<WorkerFlags>();
  CLI::App* cmd = app.add_subcommand(
      "worker", "run a worker: lease tasks from a coordinator and run them (until SIGTERM)");
  AddClientFlags(*cmd, f->client);
  cmd->add_option("--store-root", f->options.store_root,
                  "the coordinator's store root, on a filesystem both can reach (checked at start: "
                  "its .wavebake-store-root marker must be the coordinator's, and it writable)")
      ->required();
  cmd->add_option("--threads", f->options.threads, "tasks run at once")->capture_default_str();
  cmd->add_option("--scene-cache", f->options.scene_cache_dir,
                  "where fetched scenes are kept (default STORE_ROOT/.scene-cache)");
  cmd->add_option("--name", f->options.name, "shown by the coordinator (default host:pid)");
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
