// `wavebake coordinator --listen ADDR --data DIR` (DESIGN.md §4, §5): the
// job service and the work queue, until SIGINT or SIGTERM.
#include <condition_variable>
#include <fstream>
#include <memory>
#include <mutex>

#include "absl/strings/str_cat.h"
#include "cli/cluster_commands.h"
#include "cli/command_error.h"
#include "cli/signal_watcher.h"
#include "cli/stderr_log.h"
#include "coordinator/coordinator.h"
#include "coordinator/job_planner.h"
#include "driver/client.h"

namespace wavebake::cli {
namespace {

struct CoordinatorFlags {
  std::string listen;
  std::string data;
  std::string store_root;
  std::string token_file;
  std::string tls_cert, tls_key;
  double lease_seconds = 30;
  int64_t lease_wait_ms = 100;
  int64_t max_upload_mb = 1024;
  int worker_failure_limit = 3;
  std::string address_file;
};

// "host:port" for scripts that listen on port 0; appears whole (rename).
void WriteAddressFile(const std::string& path, const std::string& address) {
  const std::string temp = path + ".tmp";
  std::ofstream(temp) << address << "\n";
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) Fail("coordinator", absl::StrCat("--address-file: cannot write '", path, "'"));
}

void Run(const CoordinatorFlags& f) {
  LogToStderr(spdlog::level::info);
  std::mutex mu;
  std::condition_variable stopped;
  bool stop = false;
  SignalWatcher signals([&](int) {
    std::lock_guard lock(mu);
    stop = true;
    stopped.notify_all();
  });

  CoordinatorOptions options{.listen_address = f.listen,
                             .data_dir = f.data,
                             .store_root = f.store_root.empty()
                                               ? std::filesystem::path(f.data) / "store"
                                               : std::filesystem::path(f.store_root),
                             .lease_seconds = f.lease_seconds,
                             .max_upload_bytes = f.max_upload_mb << 20,
                             .worker_failure_limit = f.worker_failure_limit,
                             .wait_ms = f.lease_wait_ms};
  if (!f.token_file.empty()) {
    absl::StatusOr<std::string> token = driver::ReadTokenFile(f.token_file);
    if (!token.ok()) Fail("coordinator", token.status());
    options.token = *token;
  }
  options.tls_cert_path = f.tls_cert;
  options.tls_key_path = f.tls_key;
  const std::filesystem::path store_root = options.store_root;
  absl::StatusOr<std::unique_ptr<Coordinator>> coordinator = Coordinator::Start(
      options, MakeJobPlanner({.data_dir = f.data, .store_root = store_root, .local_scenes = {}}),
      MakeJobCleanup(store_root));
  if (!coordinator.ok()) Fail("coordinator", coordinator.status());
  if (!f.address_file.empty()) WriteAddressFile(f.address_file, (*coordinator)->address());

  std::unique_lock lock(mu);
  stopped.wait(lock, [&] { return stop; });
  spdlog::info("coordinator: shutting down");
  (*coordinator)->Shutdown();
}

}  // namespace

void AddCoordinatorCommand(CLI::App& app) {
  auto f = std::make_shared<CoordinatorFlags>();
  CLI::App* cmd = app.add_subcommand(
      "coordinator",
      "run the coordinator: clients submit and watch jobs, workers lease their tasks "
      "(until SIGINT/SIGTERM)");
  cmd->add_option("--listen", f->listen, "address to serve gRPC on, host:port (port 0: any free)")
      ->required();
  cmd->add_option("--data", f->data,
                  "directory of the job state (SQLite), uploaded scenes and, "
                  "by default, the store root")
      ->required();
  cmd->add_option("--store-root", f->store_root,
                  "where stores are built, shared with the workers (default DATA/store)");
  cmd->add_option("--token-file", f->token_file,
                  "require this bearer token (first line of the file) on every RPC");
  cmd->add_option("--tls-cert", f->tls_cert, "PEM certificate: serve TLS (with --tls-key)");
  cmd->add_option("--tls-key", f->tls_key, "PEM private key of --tls-cert");
  cmd->add_option("--lease-seconds", f->lease_seconds,
                  "how long a task's lease lasts without a heartbeat")
      ->capture_default_str();
  cmd->add_option("--lease-wait-ms", f->lease_wait_ms,
                  "how long an idle worker waits before asking for work again")
      ->capture_default_str();
  cmd->add_option("--max-upload-mb", f->max_upload_mb, "largest scene upload accepted")
      ->capture_default_str();
  cmd->add_option("--worker-failure-limit", f->worker_failure_limit,
                  "consecutive task failures that exclude a worker")
      ->capture_default_str();
  cmd->add_option("--address-file", f->address_file,
                  "write the address it listens on (host:port) to this file once serving");
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
