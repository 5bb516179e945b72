#pragma once
// The worker process (DESIGN.md §4 WorkerService, §5 `wavebake worker`):
// registers with the coordinator, then `threads` threads each run one task at
// a time (worker/loop/task_runner.h); the threads that are between tasks report
// their results and lease their next tasks together, in one LeaseBatch call
// (a whole worker costs the coordinator one call and one commit per round,
// not two per task), while a heartbeat thread
// renews the running leases, reports their progress counters and stops the
// tasks whose leases the coordinator withdrew. Results go back with Complete,
// errors with Fail and the task's reason.
//
// Riding out the coordinator: UNAVAILABLE and other transient errors are
// retried with backoff (a restarted coordinator voids the old leases; their
// tasks stop at the next heartbeat and are leased again), NOT_FOUND for the
// worker id means the coordinator forgot it: register again. UNAUTHENTICATED,
// PERMISSION_DENIED, FAILED_PRECONDITION (excluded) and INVALID_ARGUMENT end
// the loop with that error.
//
// `wavebake worker` runs one per process; `wavebake bake` runs several in
// its own process over the coordinator's in-process channel, sharing one
// ContextCache and SceneCache.
#include <grpcpp/channel.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/status.h"
#include "wavebake.grpc.pb.h"
#include "worker/loop/context_cache.h"
#include "worker/loop/scene_cache.h"
#include "worker/loop/task_runner.h"

namespace wavebake {

struct WorkerOptions {
  std::filesystem::path store_root{};       // required: the coordinator's store root, shared
  std::filesystem::path scene_cache_dir{};  // empty = store_root / ".scene-cache"
  int threads = 1;
  std::string name{};   // shown by the coordinator; empty = host:pid
  std::string token{};  // bearer token; empty = none
  int64_t rpc_timeout_ms = 30'000;
  int64_t heartbeat_ms = 0;        // 0 = a third of the remaining lease at grant time
  int64_t max_backoff_ms = 2'000;  // retry delay cap after transient errors
  // Shared caches (the embedded bake); null = the worker's own.
  std::shared_ptr<ContextCache> contexts{};
  std::shared_ptr<SceneCache> scenes{};
  // Staging held in memory (worker/tiles/memory_staging.h); only for loops that
  // share a process with every other worker of their jobs (the embedded
  // bake). Null: the store alone.
  std::shared_ptr<MemoryStaging> memory_staging{};
};

struct WorkerCounters {
  int64_t completed = 0;  // Complete accepted
  int64_t failed = 0;     // Fail sent
  int64_t cancelled = 0;  // stopped by a withdrawn lease
  int64_t rays_traced = 0;
  int64_t bytes_written = 0;
};

class WorkerLoop {
 public:
  WorkerLoop(std::shared_ptr<grpc::ChannelInterface> channel, WorkerOptions options);
  WorkerLoop(const WorkerLoop&) = delete;
  WorkerLoop& operator=(const WorkerLoop&) = delete;
  ~WorkerLoop();

  // Checks the store root (storage/store/store_root_marker.h: missing, foreign or
  // read-only is FailedPrecondition before any lease), registers and works
  // until Drain() (then OK, once the running tasks have finished and been
  // reported) or a fatal error (returned).
  absl::Status Run();
  // Stop leasing; tasks that are running finish and are reported. Safe from
  // any thread, also before Run.
  void Drain();
  // Drain, and stop the running tasks too: they are reported with Fail.
  void Abort();

  std::string worker_id() const;
  WorkerCounters counters() const;

 private:
  struct Running {
    std::string lease_id;
    std::shared_ptr<TaskProgress> progress;
  };
  // A finished task whose result goes with the thread's next LeaseBatch.
  struct Finished {
    v1::Task task;
    TaskOutcome outcome;
    std::chrono::steady_clock::time_point since;
  };
  // One lease thread's place in a LeaseBatch round (worker_loop_lease.cc):
  // what it brings (a result) and what it gets (a task, or how long to wait).
  struct Seat {
    std::optional<Finished> finished;
    bool served = false;
    grpc::Status status;
    std::string worker_id;  // the id the call was made with
    std::optional<v1::Task> task;
    int64_t wait_ms = 0;
  };

  absl::Status Register();
  absl::Status Reregister(const std::string& stale_id);
  void LeaseLoop();
  void TakeSeat(Seat& seat);  // joins or leads the next LeaseBatch round
  void ServeRound(const std::vector<Seat*>& round);
  void LeaseSingle(Seat& seat);  // Lease, for coordinators without LeaseBatch
  // Runs a leased task; a success is returned to be reported with the next
  // LeaseBatch, anything else is reported here.
  std::optional<Finished> RunLeased(const v1::Task& task);
  void Report(const v1::Task& task, const absl::StatusOr<TaskOutcome>& outcome);
  void HeartbeatLoop(std::stop_token stop);
  void HeartbeatOnce();
  absl::Status FetchScene(const v1::SceneRef& ref, const std::filesystem::path& dest);

  // Classifies an RPC error: fatal ones end the loop (returned), NOT_FOUND
  // re-registers, the rest wait with backoff. OK when work may go on.
  absl::Status Recover(const grpc::Status& status, const std::string& worker_id, int attempt);
  // Counts a failed TLS handshake (reset by any call that got through); the
  // error that ends the loop once there were too many.
  absl::Status CountTlsFailure(const grpc::Status& status, const char* rpc);
  void TlsWorks();
  std::unique_ptr<grpc::ClientContext> Context() const;
  bool SleepUnlessDraining(int64_t ms);  // false: draining
  void SetFatal(absl::Status status);
  bool Aborted() const;

  // How long a result is retried while the coordinator is away: a restarted
  // one still takes the result of a task that is not done (§4).
  static constexpr std::chrono::seconds kReportPatience{60};

  WorkerOptions options_;
  std::unique_ptr<v1::WorkerService::Stub> stub_;
  std::shared_ptr<ContextCache> contexts_;
  std::shared_ptr<SceneCache> scenes_;
  TaskEnv env_;

  std::mutex register_mu_;  // one re-registration at a time
  mutable std::mutex mu_;
  std::condition_variable_any wake_;  // drain, abort, a shorter heartbeat period
  std::string worker_id_;
  std::string store_root_id_;  // the coordinator's, from Register ("" from older ones)
  bool draining_ = false;
  bool aborted_ = false;
  absl::Status fatal_;
  std::map<std::string, Running> running_;  // by lease id
  std::condition_variable seats_cv_;        // a LeaseBatch round ended
  std::vector<Seat*> seats_;                // waiting for the next round
  bool leading_ = false;                    // a round is in flight
  bool batch_leases_ = true;                // false once the coordinator lacks LeaseBatch
  int64_t heartbeat_ms_ = 1'000;
  int tls_failures_ = 0;   // UNAVAILABLE calls since a TLS handshake failed
  std::string tls_error_;  // that handshake's error; empty when none since the last success
  WorkerCounters counters_;
};

}  // namespace wavebake
