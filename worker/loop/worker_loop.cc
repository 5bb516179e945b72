#include "worker/loop/worker_loop.h"

#include <grpcpp/client_context.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "storage/store/store_root_marker.h"

namespace wavebake {
namespace {

using SteadyClock = std::chrono::steady_clock;

// Errors no retry can fix: the loop ends with them.
bool IsFatal(grpc::StatusCode code) {
  return code == grpc::StatusCode::UNAUTHENTICATED || code == grpc::StatusCode::PERMISSION_DENIED ||
         code == grpc::StatusCode::FAILED_PRECONDITION ||
         code == grpc::StatusCode::INVALID_ARGUMENT || code == grpc::StatusCode::UNIMPLEMENTED;
}

absl::Status FromGrpc(const grpc::Status& s, const char* rpc) {
  // gRPC and absl share the canonical code numbers.
  return absl::Status(static_cast<absl::StatusCode>(s.error_code()),
                      absl::StrCat(rpc, ": ", s.error_message()));
}

// Only an unknown worker id is cured by registering again; the coordinator
// says so by the WorkerError in the status details (proto/wavebake.proto),
// whatever else was not found and however the message is worded.
bool UnknownWorker(const grpc::Status& s) {
  if (s.error_code() != grpc::StatusCode::NOT_FOUND) return false;
  v1::StatusDetails details;
  if (!details.ParseFromString(s.error_details())) return false;
  for (const google::protobuf::Any& any : details.details()) {
    v1::WorkerError error;
    if (any.UnpackTo(&error) && error.reason() == v1::WorkerError::UNKNOWN_WORKER) return true;
  }
  return false;
}

int64_t NowUnixMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// A TLS handshake that failed on the certificate (one the worker's --tls-ca
// does not trust, or that does not name the address dialled): gRPC reports
// it as UNAVAILABLE like a coordinator that is away, but waiting does not
// cure it. ("tcp handshaker shutdown" is a connection attempt cut short: not
// this.)
bool TlsFailure(const grpc::Status& s) {
  if (s.error_code() != grpc::StatusCode::UNAVAILABLE) return false;
  const std::string m = absl::AsciiStrToLower(s.error_message());
  return absl::StrContains(m, "ssl handshake failed") || absl::StrContains(m, "certificate") ||
         absl::StrContains(m, "ssl_error");
}

// TLS failures before the worker gives up (~1.5 s of backoff when they come
// one after another): a few, in case the coordinator is swapping its certificate.
constexpr int kTlsTries = 5;

int64_t BackoffMs(int attempt, int64_t cap) {
  return std::min<int64_t>(cap, int64_t{50} << std::min(attempt, 8));
}

std::string DefaultName() {
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0) host[0] = 0;
  return absl::StrCat(host[0] ? host : "worker", ":", ::getpid());
}

}  // namespace

WorkerLoop::WorkerLoop(std::shared_ptr<grpc::ChannelInterface> channel, WorkerOptions options)
    : options_(std::move(options)), stub_(v1::WorkerService::NewStub(channel)) {
  if (options_.name.empty()) options_.name = DefaultName();
  if (options_.scene_cache_dir.empty())
    options_.scene_cache_dir = options_.store_root / ".scene-cache";
  contexts_ = options_.contexts ? options_.contexts : std::make_shared<ContextCache>();
  scenes_ =
      options_.scenes ? options_.scenes : std::make_shared<SceneCache>(options_.scene_cache_dir);
  env_ =
      TaskEnv{.store_root = options_.store_root,
              .scenes = scenes_.get(),
              .contexts = contexts_.get(),
              .fetch = [this](const v1::SceneRef& ref,
                              const std::filesystem::path& dest) { return FetchScene(ref, dest); },
              .threads = std::max(1, options_.threads),
              .memory_staging = options_.memory_staging.get()};
}

WorkerLoop::~WorkerLoop() { Drain(); }

absl::Status WorkerLoop::Run() {
  if (options_.threads < 1 || options_.threads > 4096)
    return absl::InvalidArgumentError(
        absl::StrCat("threads: ", options_.threads, " is not in 1..4096"));
  if (options_.store_root.empty()) return absl::InvalidArgumentError("store_root: required");
  // A wrong --store-root is refused here, not by failed tasks: what can be
  // seen locally first (a directory, writable), then the marker against the
  // coordinator's id once it answers (none from coordinators without one).
  if (absl::Status s = CheckWorkerStoreRoot(options_.store_root, ""); !s.ok()) return s;
  if (absl::Status s = Register(); !s.ok()) return s;
  {
    std::lock_guard lock(mu_);
    if (draining_) return fatal_;
  }
  if (!store_root_id_.empty()) {
    if (absl::Status s = CheckWorkerStoreRoot(options_.store_root, store_root_id_); !s.ok())
      return s;
  }
  {
    std::jthread heartbeat([this](std::stop_token stop) { HeartbeatLoop(stop); });
    std::vector<std::jthread> threads;
    for (int i = 0; i < options_.threads; ++i) threads.emplace_back([this] { LeaseLoop(); });
    for (std::jthread& t : threads) t.join();
    heartbeat.request_stop();
  }
  std::lock_guard lock(mu_);
  spdlog::info("worker {}: stopped ({} tasks completed, {} failed, {} cancelled)", worker_id_,
               counters_.completed, counters_.failed, counters_.cancelled);
  return fatal_;
}

void WorkerLoop::Drain() {
  std::lock_guard lock(mu_);
  draining_ = true;
  wake_.notify_all();
}

bool WorkerLoop::Aborted() const {
  std::lock_guard lock(mu_);
  return aborted_;
}

void WorkerLoop::Abort() {
  std::lock_guard lock(mu_);
  draining_ = aborted_ = true;
  for (auto& [id, r] : running_) r.progress->cancel = true;
  wake_.notify_all();
}

std::string WorkerLoop::worker_id() const {
  std::lock_guard lock(mu_);
  return worker_id_;
}

WorkerCounters WorkerLoop::counters() const {
  std::lock_guard lock(mu_);
  return counters_;
}

std::unique_ptr<grpc::ClientContext> WorkerLoop::Context() const {
  auto ctx = std::make_unique<grpc::ClientContext>();
  ctx->set_deadline(std::chrono::system_clock::now() +
                    std::chrono::milliseconds(options_.rpc_timeout_ms));
  if (!options_.token.empty()) ctx->AddMetadata("authorization", "Bearer " + options_.token);
  return ctx;
}

bool WorkerLoop::SleepUnlessDraining(int64_t ms) {
  std::unique_lock lock(mu_);
  wake_.wait_for(lock, std::chrono::milliseconds(ms), [&] { return draining_; });
  return !draining_;
}

void WorkerLoop::SetFatal(absl::Status status) {
  std::lock_guard lock(mu_);
  spdlog::error("worker {}: {}", worker_id_, status.ToString());
  if (fatal_.ok()) fatal_ = std::move(status);
  draining_ = true;
  wake_.notify_all();
}

// Retries while the coordinator is unreachable (it may be starting, or
// restarting), until Drain; a TLS failure only kTlsTries times.
absl::Status WorkerLoop::Register() {
  v1::WorkerInfo info;
  info.set_name(options_.name);
  info.set_threads(options_.threads);
  for (int attempt = 0;; ++attempt) {
    v1::WorkerId id;
    const grpc::Status s = stub_->Register(Context().get(), info, &id);
    if (s.ok()) {
      TlsWorks();
      std::lock_guard lock(mu_);
      worker_id_ = id.id();
      store_root_id_ = id.store_root_id();
      spdlog::info("worker {}: registered as \"{}\" with {} thread(s)", worker_id_, options_.name,
                   options_.threads);
      return absl::OkStatus();
    }
    if (IsFatal(s.error_code())) return FromGrpc(s, "Register");
    if (absl::Status tls = CountTlsFailure(s, "Register"); !tls.ok()) return tls;
    if (attempt % 20 == 0) spdlog::warn("worker: Register: {} (retrying)", s.error_message());
    if (!SleepUnlessDraining(BackoffMs(attempt, options_.max_backoff_ms))) return absl::OkStatus();
  }
}

absl::Status WorkerLoop::Reregister(const std::string& stale_id) {
  std::lock_guard lock(register_mu_);                    // one re-registration for all threads
  if (worker_id() != stale_id) return absl::OkStatus();  // another thread did it
  spdlog::warn("worker {}: the coordinator does not know this worker; registering again", stale_id);
  return Register();
}

absl::Status WorkerLoop::Recover(const grpc::Status& status, const std::string& worker_id,
                                 int attempt) {
  if (UnknownWorker(status)) return Reregister(worker_id);
  if (IsFatal(status.error_code())) return FromGrpc(status, "WorkerService");
  if (absl::Status tls = CountTlsFailure(status, "WorkerService"); !tls.ok()) return tls;
  if (attempt % 20 == 0)
    spdlog::warn("worker {}: {} (retrying)", worker_id, status.error_message());
  SleepUnlessDraining(BackoffMs(attempt, options_.max_backoff_ms));
  return absl::OkStatus();
}

// After a handshake failed, gRPC backs off reconnecting and later calls fail
// fast with other UNAVAILABLE messages: until a call gets through, they count
// too, and the error quotes the handshake's.
absl::Status WorkerLoop::CountTlsFailure(const grpc::Status& status, const char* rpc) {
  std::lock_guard lock(mu_);
  if (TlsFailure(status)) tls_error_ = status.error_message();
  if (tls_error_.empty() || status.error_code() != grpc::StatusCode::UNAVAILABLE)
    return absl::OkStatus();
  if (++tls_failures_ < kTlsTries) return absl::OkStatus();
  return absl::UnavailableError(absl::StrCat(
      rpc, ": TLS: no trusted connection to the coordinator after ", kTlsTries,
      " tries (check --tls-ca and that the coordinator's certificate names the address "
      "dialled): ",
      tls_error_));
}

void WorkerLoop::TlsWorks() {
  std::lock_guard lock(mu_);
  tls_failures_ = 0;
  tls_error_.clear();
}

std::optional<WorkerLoop::Finished> WorkerLoop::RunLeased(const v1::Task& task) {
  // Renew at a third of the lease: two heartbeats may be lost before it expires.
  const int64_t remaining = task.lease_deadline_ms() - NowUnixMs();
  auto progress = std::make_shared<TaskProgress>();
  {
    std::lock_guard lock(mu_);
    heartbeat_ms_ = options_.heartbeat_ms > 0 ? options_.heartbeat_ms
                    : remaining > 0           ? std::clamp<int64_t>(remaining / 3, 20, 10'000)
                                              : 1'000;
    running_[task.lease_id()] = {task.lease_id(), progress};
    if (aborted_) progress->cancel = true;
    wake_.notify_all();  // the heartbeat thread may be waiting out a longer period
  }
  const auto start = SteadyClock::now();
  absl::StatusOr<TaskOutcome> outcome = RunTask(task, env_, *progress);
  {
    std::lock_guard lock(mu_);
    running_.erase(task.lease_id());
  }
  spdlog::info("job {} {} {}: {} in {:.2f} s", task.job_id(), v1::TaskKind_Name(task.kind()),
               task.index(), outcome.ok() ? "done" : outcome.status().ToString(),
               std::chrono::duration<double>(SteadyClock::now() - start).count());
  {
    std::lock_guard lock(mu_);
    if (outcome.ok() && batch_leases_ && !aborted_) {
      return Finished{task, *std::move(outcome), SteadyClock::now()};
    }
  }
  Report(task, outcome);
  return std::nullopt;
}

void WorkerLoop::Report(const v1::Task& task, const absl::StatusOr<TaskOutcome>& outcome) {
  bool aborted;
  {
    std::lock_guard lock(mu_);
    aborted = aborted_;
    if (absl::IsCancelled(outcome.status()) && !aborted) {
      ++counters_.cancelled;  // the coordinator withdrew the lease: it wants nothing back
      return;
    }
  }
  const auto start = SteadyClock::now();
  for (int attempt = 0;; ++attempt) {
    // Aborted (the process is ending): one second of tries, not the patience.
    const auto give_up = start + (Aborted() ? std::chrono::seconds(1) : kReportPatience);
    const std::string id = worker_id();
    grpc::Status s;
    bool accepted = false;
    if (outcome.ok()) {
      v1::TaskResult result;
      result.set_worker_id(id);
      result.set_lease_id(task.lease_id());
      result.set_rays_traced(outcome->rays_traced);
      result.set_bytes_written(outcome->bytes_written);
      result.set_stats_json(outcome->stats_json);
      v1::CompleteReply reply;
      s = stub_->Complete(Context().get(), result, &reply);
      accepted = reply.accepted();
    } else {
      v1::TaskFailure failure;
      failure.set_worker_id(id);
      failure.set_lease_id(task.lease_id());
      failure.set_reason(aborted && absl::IsCancelled(outcome.status())
                             ? absl::StrCat("worker \"", options_.name, "\" was stopped")
                             : outcome.status().ToString());
      // INVALID_ARGUMENT is the task's input (scene, parameters) naming its
      // bad field: every worker would fail the same way (DESIGN.md §4).
      // RESOURCE_EXHAUSTED is a full disk under the shared store root: a
      // retry writes to the same disk.
      failure.set_permanent(!aborted && (absl::IsInvalidArgument(outcome.status()) ||
                                         absl::IsResourceExhausted(outcome.status())));
      v1::FailReply reply;
      s = stub_->Fail(Context().get(), failure, &reply);
    }
    if (s.ok()) {
      std::lock_guard lock(mu_);
      if (!outcome.ok()) {
        ++counters_.failed;
      } else if (accepted) {
        ++counters_.completed;
        counters_.rays_traced += outcome->rays_traced;
        counters_.bytes_written += outcome->bytes_written;
      }
      return;
    }
    if (UnknownWorker(s)) {
      if (absl::Status r = Reregister(id); !r.ok()) return SetFatal(r);
      continue;  // any worker may complete a task that is not done yet
    }
    if (IsFatal(s.error_code()) || s.error_code() == grpc::StatusCode::NOT_FOUND ||
        SteadyClock::now() > give_up) {
      // The lease's expiry gives the task to another worker.
      spdlog::warn("worker {}: cannot report job {} task {}: {}", id, task.job_id(),
                   task.lease_id(), s.error_message());
      return;
    }
    std::this_thread::sleep_for(
        std::chrono::milliseconds(BackoffMs(attempt, options_.max_backoff_ms)));
  }
}

void WorkerLoop::HeartbeatLoop(std::stop_token stop) {
  while (!stop.stop_requested()) {
    {
      std::unique_lock lock(mu_);
      const int64_t period = heartbeat_ms_;
      wake_.wait_for(lock, stop, std::chrono::milliseconds(period),
                     [&] { return heartbeat_ms_ < period; });
      if (heartbeat_ms_ < period) continue;  // a shorter lease came: wait that long instead
    }
    if (stop.stop_requested()) return;
    HeartbeatOnce();
  }
}

void WorkerLoop::HeartbeatOnce() {
  std::vector<Running> leases;
  std::string id;
  {
    std::lock_guard lock(mu_);
    for (const auto& [lease, r] : running_) leases.push_back(r);
    id = worker_id_;
  }
  if (leases.empty()) return;
  v1::HeartbeatRequest request;
  request.set_worker_id(id);
  for (const Running& r : leases) {
    v1::LeaseProgress* p = request.add_leases();
    p->set_lease_id(r.lease_id);
    p->set_rays_traced(static_cast<int64_t>(r.progress->rays_traced.load()));
    p->set_bytes_written(static_cast<int64_t>(r.progress->bytes_written.load()));
  }
  v1::HeartbeatReply reply;
  const grpc::Status s = stub_->Heartbeat(Context().get(), request, &reply);
  if (s.ok()) {
    for (const std::string& cancelled : reply.cancelled_lease_ids()) {
      for (const Running& r : leases) {
        if (r.lease_id != cancelled) continue;
        spdlog::info("worker {}: lease {} withdrawn; stopping its task", id, cancelled);
        r.progress->cancel = true;
      }
    }
  } else if (UnknownWorker(s)) {
    // The coordinator forgot this worker, and with it every lease it held.
    for (const Running& r : leases) r.progress->cancel = true;
    if (absl::Status r = Reregister(id); !r.ok()) SetFatal(r);
  } else {
    spdlog::warn("worker {}: Heartbeat: {}", id, s.error_message());
  }
}

absl::Status WorkerLoop::FetchScene(const v1::SceneRef& ref, const std::filesystem::path& dest) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() +
                   std::chrono::milliseconds(10 * options_.rpc_timeout_ms));
  if (!options_.token.empty()) ctx.AddMetadata("authorization", "Bearer " + options_.token);
  std::unique_ptr<grpc::ClientReader<v1::SceneChunk>> reader = stub_->FetchScene(&ctx, ref);
  std::ofstream out(dest, std::ios::binary | std::ios::trunc);
  int64_t received = 0, size = -1;
  v1::SceneChunk chunk;
  bool in_order = true;
  while (reader->Read(&chunk)) {
    if (received == 0 && chunk.size() > 0) size = chunk.size();
    in_order = in_order && chunk.offset() == received;
    out.write(chunk.data().data(), static_cast<std::streamsize>(chunk.data().size()));
    received += static_cast<int64_t>(chunk.data().size());
  }
  const grpc::Status s = reader->Finish();
  if (!s.ok()) return FromGrpc(s, "FetchScene");
  out.close();
  if (!out) return absl::InternalError(absl::StrCat("scene cache: cannot write ", dest.string()));
  if (!in_order || (size >= 0 && received != size) || (ref.size() > 0 && received != ref.size())) {
    return absl::DataLossError(absl::StrCat("FetchScene: scene ", ref.sha256(), ": got ", received,
                                            " bytes, expected ", std::max(size, ref.size())));
  }
  return absl::OkStatus();
}

}  // namespace wavebake
