#include "coordinator/service/coordinator.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server_builder.h>
#include <spdlog/spdlog.h>

#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "coordinator/state/orphan_stores.h"
#include "storage/store/store_root_marker.h"

namespace wavebake {
namespace {

absl::StatusOr<std::string> ReadFile(const std::filesystem::path& path, absl::string_view field) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::InvalidArgumentError(absl::StrCat(field, ": cannot read ", path.string()));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> Credentials(const CoordinatorOptions& o) {
  if (o.tls_cert_path.empty() != o.tls_key_path.empty()) {
    return absl::InvalidArgumentError("tls_cert/tls_key: give both or neither");
  }
  if (o.tls_cert_path.empty()) return grpc::InsecureServerCredentials();
  absl::StatusOr<std::string> cert = ReadFile(o.tls_cert_path, "tls_cert");
  if (!cert.ok()) return cert.status();
  absl::StatusOr<std::string> key = ReadFile(o.tls_key_path, "tls_key");
  if (!key.ok()) return key.status();
  grpc::SslServerCredentialsOptions ssl;
  ssl.pem_key_cert_pairs.push_back({*key, *cert});
  return grpc::SslServerCredentials(ssl);
}

// The default cleanup: remove the job's (partial) store directory.
CleanupFn RemoveStoreDir(std::filesystem::path store_root) {
  return [root = std::move(store_root)](const JobRecord& job) {
    std::error_code ec;
    std::filesystem::remove_all(root / job.store_path, ec);
    if (ec) spdlog::warn("job {}: cannot remove {}: {}", job.id, job.store_path, ec.message());
  };
}

}  // namespace

absl::StatusOr<std::unique_ptr<Coordinator>> Coordinator::Start(CoordinatorOptions options,
                                                                PlanFn plan_fn,
                                                                CleanupFn cleanup_fn) {
  if (options.data_dir.empty()) return absl::InvalidArgumentError("data_dir: required");
  if (!plan_fn) return absl::InvalidArgumentError("plan_fn: required");
  if (!(options.lease_seconds > 0)) {
    return absl::InvalidArgumentError(
        absl::StrCat("lease_seconds: ", options.lease_seconds, " is not positive"));
  }
  if (options.store_root.empty()) options.store_root = options.data_dir / "store";
  // Absolute, so every message spells them one way (ClientPaths hides them).
  std::error_code ec;
  options.data_dir = std::filesystem::absolute(options.data_dir, ec);
  options.store_root = std::filesystem::absolute(options.store_root, ec);
  auto c = std::make_unique<Coordinator>(Key{});
  c->options_ = std::move(options);
  if (absl::Status s = c->Init(std::move(plan_fn), std::move(cleanup_fn)); !s.ok()) return s;
  return c;
}

absl::Status Coordinator::Init(PlanFn plan_fn, CleanupFn cleanup_fn) {
  const CoordinatorOptions& o = options_;
  std::error_code ec;
  for (const auto& dir : {o.data_dir, o.store_root}) {
    std::filesystem::create_directories(dir, ec);
    if (ec)
      return absl::InvalidArgumentError(
          absl::StrCat("data_dir: ", dir.string(), ": ", ec.message()));
  }
  absl::StatusOr<DataDirLock> lock = DataDirLock::Acquire(o.data_dir, "data_dir");
  if (!lock.ok()) return lock.status();
  lock_ = std::move(*lock);
  // The store root too, when it is not the data dir: two coordinators on one
  // store root would name their jobs' stores alike and remove each other's
  // partial stores as orphans.
  if (!std::filesystem::equivalent(o.data_dir, o.store_root, ec)) {
    absl::StatusOr<DataDirLock> root_lock = DataDirLock::Acquire(o.store_root, "store_root");
    if (!root_lock.ok()) return root_lock.status();
    store_root_lock_ = std::move(*root_lock);
  }
  // Workers compare this with the marker at their --store-root at start.
  absl::StatusOr<std::string> store_root_id = EnsureStoreRootMarker(o.store_root);
  if (!store_root_id.ok()) return store_root_id.status();
  const Clock* clock = o.clock ? o.clock : SystemClock::Get();
  absl::StatusOr<std::unique_ptr<JobStore>> store =
      JobStore::Open((o.data_dir / "state.sqlite").string());
  if (!store.ok()) return store.status();
  store_ = std::move(*store);
  if (!cleanup_fn) cleanup_fn = RemoveStoreDir(o.store_root);
  LeaseTableOptions lease_options{.lease_ms = static_cast<int64_t>(o.lease_seconds * 1000),
                                  .worker_failure_limit = o.worker_failure_limit};
  absl::StatusOr<std::unique_ptr<LeaseTable>> table =
      LeaseTable::Create(store_.get(), clock, lease_options, std::move(cleanup_fn));
  if (!table.ok()) return table.status();
  table_ = std::move(*table);
  {
    std::set<std::string> live;
    for (const JobInfo& job : table_->List(std::numeric_limits<int>::max(), /*active_only=*/true))
      live.insert(job.record.store_path);
    if (absl::StatusOr<int> removed = RemoveOrphanPartialStores(o.store_root, live); !removed.ok())
      spdlog::warn("coordinator: {}", removed.status().ToString());
  }
  scenes_ = std::make_unique<SceneStore>(o.data_dir, store_.get(), clock, o.max_upload_bytes);
  auth_ = std::make_unique<TokenAuth>(o.token);
  ServiceDeps deps{.table = table_.get(),
                   .scenes = scenes_.get(),
                   .auth = auth_.get(),
                   .plan = std::move(plan_fn),
                   .store_root = o.store_root,
                   .store_root_id = *store_root_id,
                   .wait_ms = o.wait_ms,
                   .stopping = &stopping_,
                   .client_paths = {}};
  if (o.hide_paths) {
    deps.client_paths.Hide(o.data_dir, "<data dir>");
    deps.client_paths.Hide(o.store_root, "<store root>");
    deps.hide_worker_paths = true;
  }
  job_service_ = std::make_unique<JobServiceImpl>(deps);
  worker_service_ = std::make_unique<WorkerServiceImpl>(deps);
  if (absl::Status s = BuildServer(); !s.ok()) return s;
  reaper_ = std::jthread([this](std::stop_token stop) { ReapLoop(stop); });
  return absl::OkStatus();
}

absl::Status Coordinator::BuildServer() {
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  if (!options_.listen_address.empty()) {
    absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> creds = Credentials(options_);
    if (!creds.ok()) return creds.status();
    builder.AddListeningPort(options_.listen_address, *creds, &port_);
  }
  builder.SetMaxReceiveMessageSize(options_.max_message_bytes);
  builder.SetMaxSendMessageSize(options_.max_message_bytes);
  builder.RegisterService(job_service_.get());
  builder.RegisterService(worker_service_.get());
  server_ = builder.BuildAndStart();
  if (!server_ || (!options_.listen_address.empty() && port_ == 0)) {
    return absl::UnavailableError(
        absl::StrCat("listen_address: cannot listen on \"", options_.listen_address, "\""));
  }
  spdlog::info("coordinator: listening on {} (data {})", address(), options_.data_dir.string());
  return BuildHealthServer();
}

// A server with no service of ours: the default health service alone. Its
// overall status ("") follows the main port's (NOT_SERVING while the table
// cannot record a change: a readiness probe); kLivenessService answers
// SERVING while the process serves, full disk or not (a liveness probe: a
// restart would not free the disk, and the coordinator recovers without one).
absl::Status Coordinator::BuildHealthServer() {
  if (options_.health_address.empty()) return absl::OkStatus();
  grpc::ServerBuilder builder;
  builder.AddListeningPort(options_.health_address, grpc::InsecureServerCredentials(),
                           &health_port_);
  health_server_ = builder.BuildAndStart();
  if (!health_server_ || health_port_ == 0) {
    return absl::UnavailableError(
        absl::StrCat("health_address: cannot listen on \"", options_.health_address, "\""));
  }
  health_server_->GetHealthCheckService()->SetServingStatus(kLivenessService, true);
  spdlog::info("coordinator: health service alone, in plain text, on port {}", health_port_);
  return absl::OkStatus();
}

// Expires leases even when no worker calls (Lease and Heartbeat expire too),
// so watchers see requeues promptly.
void Coordinator::ReapLoop(std::stop_token stop) {
  const int64_t period_ms = std::clamp<int64_t>(table_->options().lease_ms / 4, 10, 1000);
  std::unique_lock lock(reap_mu_);
  absl::Status last_error;
  grpc::HealthCheckServiceInterface* health = server_->GetHealthCheckService();
  grpc::HealthCheckServiceInterface* probe_health =
      health_server_ ? health_server_->GetHealthCheckService() : nullptr;
  while (!stop.stop_requested()) {
    reap_cv_.wait_for(lock, stop, std::chrono::milliseconds(period_ms), [] { return false; });
    if (stop.stop_requested()) break;
    // Also the recovery of a stopped table (a full disk freed since).
    absl::Status s = table_->ExpireLeases();
    // Once per distinct error: a stopped table fails every tick the same way.
    if (!s.ok() && s != last_error) spdlog::error("coordinator: {}", s.ToString());
    if (s.ok() && !last_error.ok()) spdlog::info("coordinator: recovered; serving again");
    // Health says what the table can do: NOT_SERVING while it cannot
    // record a change (clients and probes see it, not a SERVING that fails).
    if (s.ok() != last_error.ok()) {
      if (health) health->SetServingStatus(s.ok());
      if (probe_health) probe_health->SetServingStatus("", s.ok());
    }
    last_error = s;
  }
}

std::string Coordinator::address() const {
  if (port_ == 0) return "in-process";
  const std::string& a = options_.listen_address;
  return absl::StrCat(a.substr(0, a.rfind(':')), ":", port_);
}

std::shared_ptr<grpc::Channel> Coordinator::InProcessChannel() {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(options_.max_message_bytes);
  args.SetMaxSendMessageSize(options_.max_message_bytes);
  return server_->InProcessChannel(args);
}

void Coordinator::Shutdown() {
  if (stopping_.exchange(true)) return;
  reaper_.request_stop();
  // Probes fail first: a stopping coordinator is neither ready nor alive.
  if (health_server_) health_server_->Shutdown(std::chrono::system_clock::now());
  if (server_) server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  if (reaper_.joinable()) reaper_.join();
}

Coordinator::~Coordinator() { Shutdown(); }

}  // namespace wavebake
