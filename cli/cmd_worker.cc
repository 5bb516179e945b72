// `wavebake worker --coordinator ADDR --store-root DIR` (DESIGN.md §4, §5):
// leases tasks and runs them until SIGTERM or SIGINT, which drains it (no new
// task; the running ones finish and are reported, then exit 0). A second
// signal stops the running tasks too (reported as failed).
#include <spdlog/spdlog.h>

#include <thread>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/signal_watcher.h"
#include "worker/worker_loop.h"

namespace wavebake::cli {
namespace {

struct WorkerFlags {
  driver::ClientConfig client;
  std::string store_root;
  std::string scene_cache;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string name;
};

void Run(const WorkerFlags& f) {
  spdlog::set_level(spdlog::level::info);  // its log is its output
  WorkerLoop* running = nullptr;
  std::mutex mu;
  int signals_seen = 0;
  SignalWatcher signals([&](int) {
    std::lock_guard lock(mu);
    if (!running) {
      ++signals_seen;  // Run drains at once
      return;
    }
    if (signals_seen++ == 0) {
      spdlog::info("worker: draining (finishing the running tasks; signal again to stop them)");
      running->Drain();
    } else {
      running->Abort();
    }
  });
  // No waiting here: the loop registers as soon as the coordinator is up.
  absl::StatusOr<driver::Client> client = driver::Client::Connect(f.client, /*connect_seconds=*/0);
  if (!client.ok()) Fail("worker", client.status());
  WorkerLoop loop(client->channel(), {.store_root = f.store_root,
                                      .scene_cache_dir = f.scene_cache,
                                      .threads = f.threads,
                                      .name = f.name,
                                      .token = client->token()});
  {
    std::lock_guard lock(mu);
    running = &loop;
    if (signals_seen > 0) loop.Drain();
  }
  const absl::Status status = loop.Run();
  {
    std::lock_guard lock(mu);
    running = nullptr;
  }
  if (!status.ok()) Fail("worker", status);
}

}  // namespace

void AddWorkerCommand(CLI::App& app) {
  auto f = std::make_shared<WorkerFlags>();
  CLI::App* cmd = app.add_subcommand(
      "worker", "run a worker: lease tasks from a coordinator and run them (until SIGTERM)");
  AddClientFlags(*cmd, f->client);
  cmd->add_option("--store-root", f->store_root,
                  "the coordinator's store root, on a filesystem both can reach (checked at start: "
                  "its .wavebake-store-root marker must be the coordinator's, and it writable)")
      ->required();
  cmd->add_option("--threads", f->threads, "tasks run at once")->capture_default_str();
  cmd->add_option("--scene-cache", f->scene_cache,
                  "where fetched scenes are kept (default STORE_ROOT/.scene-cache)");
  cmd->add_option("--name", f->name, "shown by the coordinator (default host:pid)");
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
