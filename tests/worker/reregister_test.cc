// A worker registers again exactly when the coordinator says it does not
// know the worker — by the WorkerError reason in the status details
// (proto/wavebake.proto), whatever the message says — and not on a NOT_FOUND
// without that reason, even one worded like the coordinator's own.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "tests/testing/scratch_dir.h"
#include "wavebake.grpc.pb.h"
#include "worker/loop/worker_loop.h"

namespace wavebake {
namespace {

// Forgets the first worker id it gave out: every Lease by it is NOT_FOUND
// with `message` and, if `with_reason`, WorkerError UNKNOWN_WORKER.
class ForgetfulCoordinator final : public v1::WorkerService::Service {
 public:
  ForgetfulCoordinator(std::string message, bool with_reason)
      : message_(std::move(message)), with_reason_(with_reason) {}

  grpc::Status Register(grpc::ServerContext*, const v1::WorkerInfo*, v1::WorkerId* id) override {
    id->set_id(std::to_string(++registrations));
    return grpc::Status::OK;
  }
  grpc::Status Lease(grpc::ServerContext*, const v1::LeaseRequest* request,
                     v1::LeaseReply* reply) override {
    if (request->worker_id() != "1") {
      ++leases_by_new_id;
      reply->set_wait_ms(5);
      return grpc::Status::OK;
    }
    ++refused;
    if (!with_reason_) return {grpc::StatusCode::NOT_FOUND, message_};
    v1::WorkerError error;
    error.set_reason(v1::WorkerError::UNKNOWN_WORKER);
    v1::StatusDetails details;
    details.set_code(grpc::StatusCode::NOT_FOUND);
    details.set_message(message_);
    details.add_details()->PackFrom(error);
    return {grpc::StatusCode::NOT_FOUND, message_, details.SerializeAsString()};
  }

  std::atomic<int> registrations{0}, refused{0}, leases_by_new_id{0};

 private:
  std::string message_;
  bool with_reason_;
};

struct Outcome {
  int registrations = 0, refused = 0, leases_by_new_id = 0;
};

// Runs a one-thread worker against the fake until it leased as a new id or
// `seconds` passed.
Outcome RunWorker(ForgetfulCoordinator& fake, double seconds) {
  grpc::ServerBuilder builder;
  builder.RegisterService(&fake);
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  test_support::ScratchDir store;
  WorkerLoop loop(server->InProcessChannel({}),
                  {.store_root = store.path(), .threads = 1, .name = "test", .max_backoff_ms = 20});
  std::thread run([&] { (void)loop.Run(); });
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (fake.leases_by_new_id == 0 && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  loop.Drain();
  run.join();
  server->Shutdown();
  return {fake.registrations, fake.refused, fake.leases_by_new_id};
}

TEST(ReregisterTest, TheReasonNotTheWordingMakesTheWorkerRegisterAgain) {
  for (const char* message : {"worker_id: unknown worker 1", "who are you?", ""}) {
    ForgetfulCoordinator fake(message, /*with_reason=*/true);
    const Outcome o = RunWorker(fake, 10);
    EXPECT_EQ(o.registrations, 2) << "message \"" << message << "\"";
    EXPECT_GE(o.refused, 1);
    EXPECT_GE(o.leases_by_new_id, 1) << "message \"" << message << "\"";
  }
}

TEST(ReregisterTest, ANotFoundWithoutTheReasonIsNotAForgottenWorker) {
  ForgetfulCoordinator fake("worker_id: unknown worker 1", /*with_reason=*/false);
  const Outcome o = RunWorker(fake, 0.5);
  EXPECT_EQ(o.registrations, 1);
  EXPECT_GE(o.refused, 2);  // retried as a transient error, not re-registered
  EXPECT_EQ(o.leases_by_new_id, 0);
}

}  // namespace
}  // namespace wavebake
