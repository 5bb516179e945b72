#pragma once
// A tiny worker that speaks the real WorkerService over gRPC: registers,
// leases, heartbeats with progress, writes a token store file at FINALIZE
// and completes. Stands in for worker/ (not this module's) in tests.
#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "core/bake/finalize_shards.h"
#include "wavebake.grpc.pb.h"

namespace wavebake::testing {

inline std::unique_ptr<grpc::ClientContext> CallContext(const std::string& token,
                                                        int timeout_ms = 10'000) {
  auto ctx = std::make_unique<grpc::ClientContext>();
  ctx->set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(timeout_ms));
  if (!token.empty()) ctx->AddMetadata("authorization", "Bearer " + token);
  return ctx;
}

class FakeWorker {
 public:
  FakeWorker(std::shared_ptr<grpc::Channel> channel, std::string token,
             std::filesystem::path store_root)
      : stub_(v1::WorkerService::NewStub(channel)),
        token_(std::move(token)),
        store_root_(std::move(store_root)) {}
  ~FakeWorker() { Stop(); }

  void Start() {
    thread_ = std::jthread([this](std::stop_token stop) { Run(stop); });
  }
  void Stop() {
    thread_.request_stop();
    if (thread_.joinable()) thread_.join();
  }
  int completed() const { return completed_; }
  const grpc::Status& last_error() const { return last_error_; }

 private:
  void Run(std::stop_token stop) {
    v1::WorkerInfo info;
    info.set_name("fake");
    info.set_threads(1);
    v1::WorkerId id;
    if (!(last_error_ = stub_->Register(CallContext(token_).get(), info, &id)).ok()) return;
    while (!stop.stop_requested()) {
      v1::LeaseRequest req;
      req.set_worker_id(id.id());
      v1::LeaseReply reply;
      if (!(last_error_ = stub_->Lease(CallContext(token_).get(), req, &reply)).ok()) return;
      if (reply.has_task()) {
        if (!(last_error_ = Work(id.id(), reply.task())).ok()) return;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(reply.wait_ms()));
      }
    }
  }

  grpc::Status Work(const std::string& worker_id, const v1::Task& task) {
    v1::HeartbeatRequest hb;
    hb.set_worker_id(worker_id);
    v1::LeaseProgress* p = hb.add_leases();
    p->set_lease_id(task.lease_id());
    p->set_rays_traced(100);
    v1::HeartbeatReply hb_reply;
    if (grpc::Status s = stub_->Heartbeat(CallContext(token_).get(), hb, &hb_reply); !s.ok())
      return s;
    if (hb_reply.renewed_lease_ids_size() != 1) return grpc::Status::OK;  // cancelled: drop it
    v1::TaskResult result;
    result.set_worker_id(worker_id);
    result.set_lease_id(task.lease_id());
    result.set_rays_traced(task.kind() == v1::BAKE_TILE ? 1000 : 0);
    result.set_bytes_written(10);
    if (task.kind() == v1::FINALIZE && task.index() == FinalizeShards(task.groups())) {
      const std::filesystem::path dir = store_root_ / task.store_path();
      std::filesystem::create_directories(dir / "transport");
      std::ofstream(dir / ".zgroup") << R"({"zarr_format": 2})";
      std::ofstream(dir / "transport" / "data") << std::string(3000, 'x');
      result.set_stats_json(R"({"rel_rms": 0.01})");
    }
    v1::CompleteReply done;
    grpc::Status s = stub_->Complete(CallContext(token_).get(), result, &done);
    if (s.ok() && done.accepted()) ++completed_;
    return s;
  }

  std::unique_ptr<v1::WorkerService::Stub> stub_;
  std::string token_;
  std::filesystem::path store_root_;
  std::atomic<int> completed_{0};
  grpc::Status last_error_;
  std::jthread thread_;
};

}  // namespace wavebake::testing
