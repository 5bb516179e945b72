#pragma once
// The coordinator process (DESIGN.md §4, §5 `wavebake coordinator`): owns the
// SQLite JobStore, the LeaseTable, the scene store, both gRPC services and
// the grpc::Server. The same object serves `wavebake bake` in one process:
// workers then talk to it through InProcessChannel().
//
// Files under data_dir: state.sqlite (+ WAL), scenes/<sha256>, the store
// root (default data_dir/store) that workers share (--store-root), and
// .wavebake-coordinator.lock, which keeps a second coordinator off the same data_dir
// (coordinator/state/data_dir_lock.h).
#include <grpcpp/channel.h>
#include <grpcpp/server.h>

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "absl/status/statusor.h"
#include "coordinator/scheduling/lease_table.h"
#include "coordinator/service/auth.h"
#include "coordinator/service/job_service.h"
#include "coordinator/service/worker_service.h"
#include "coordinator/state/data_dir_lock.h"
#include "coordinator/state/job_store.h"
#include "coordinator/state/scene_store.h"

namespace wavebake {

// The health service name of --health-listen's liveness answer
// (CoordinatorOptions::health_address).
inline constexpr char kLivenessService[] = "liveness";

struct CoordinatorOptions {
  std::string listen_address = "127.0.0.1:0";  // port 0 picks a free one; "" = in-process only
  std::filesystem::path data_dir{};            // required
  std::filesystem::path store_root{};          // empty = data_dir / "store"
  std::string token{};                         // empty = no auth
  std::filesystem::path tls_cert_path{}, tls_key_path{};  // both or neither (PEM)
  // Also serve only the standard gRPC health service, in plain text, here
  // ("" = not): Kubernetes' built-in grpc probes speak no TLS, and this port
  // carries no job or worker call, so no token crosses it unencrypted. Its
  // service "" is the main port's status (readiness), kLivenessService is
  // SERVING while the process serves (liveness).
  std::string health_address{};
  double lease_seconds = 30;
  int64_t max_upload_bytes = int64_t{1} << 30;
  int max_message_bytes = 16 << 20;  // gRPC send/receive limit; chunks are 1 MiB
  int worker_failure_limit = 3;      // consecutive failures that exclude a worker
  int64_t wait_ms = 500;             // LeaseReply.wait_ms when no task is ready
  const Clock* clock = nullptr;      // null = system clock
  // Replace data_dir and store_root in messages to clients (DESIGN.md §4);
  // off for the embedded bake, whose client is the user of this machine.
  bool hide_paths = true;
};

class Coordinator {
  struct Key {};

 public:
  // plan_fn: required. cleanup_fn: may be null, then a FAILED or CANCELLED
  // job's store directory (store_root / store_path) is removed.
  static absl::StatusOr<std::unique_ptr<Coordinator>> Start(CoordinatorOptions options,
                                                            PlanFn plan_fn, CleanupFn cleanup_fn);
  explicit Coordinator(Key) {}
  ~Coordinator();

  // Stops accepting calls, ends Watch streams, waits for running calls.
  void Shutdown();

  int port() const { return port_; }                // 0 when in-process only
  int health_port() const { return health_port_; }  // 0 without health_address
  std::string address() const;                      // "host:port" clients dial
  std::shared_ptr<grpc::Channel> InProcessChannel();
  grpc::Server* server() { return server_.get(); }
  LeaseTable& table() { return *table_; }
  SceneStore& scenes() { return *scenes_; }
  JobStore& job_store() { return *store_; }  // the database (tests inject a full disk)
  const CoordinatorOptions& options() const { return options_; }

 private:
  absl::Status Init(PlanFn plan_fn, CleanupFn cleanup_fn);
  absl::Status BuildServer();
  absl::Status BuildHealthServer();
  void ReapLoop(std::stop_token stop);

  CoordinatorOptions options_;
  std::optional<DataDirLock> lock_;  // before the store: released after it closes
  std::optional<DataDirLock> store_root_lock_;
  std::unique_ptr<JobStore> store_;
  std::unique_ptr<LeaseTable> table_;
  std::unique_ptr<SceneStore> scenes_;
  std::unique_ptr<TokenAuth> auth_;
  std::unique_ptr<JobServiceImpl> job_service_;
  std::unique_ptr<WorkerServiceImpl> worker_service_;
  std::unique_ptr<grpc::Server> server_;
  std::unique_ptr<grpc::Server> health_server_;  // health_address: the health service alone
  int health_port_ = 0;
  std::atomic<bool> stopping_{false};
  int port_ = 0;
  std::mutex reap_mu_;
  std::condition_variable_any reap_cv_;
  std::jthread reaper_;  // last member: stopped and joined first
};

}  // namespace wavebake
