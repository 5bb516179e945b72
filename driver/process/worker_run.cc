#include "driver/process/worker_run.h"

#include <spdlog/spdlog.h>

namespace wavebake::driver {

absl::Status WorkerRun::Run(std::shared_ptr<grpc::ChannelInterface> channel,
                            WorkerOptions options) {
  WorkerLoop loop(std::move(channel), std::move(options));
  {
    std::lock_guard lock(mu_);
    running_ = &loop;
    if (stops_ > 0) loop.Drain();
  }
  const absl::Status status = loop.Run();
  std::lock_guard lock(mu_);
  running_ = nullptr;
  return status;
}

void WorkerRun::Stop() {
  std::lock_guard lock(mu_);
  if (!running_) {
    ++stops_;  // Run drains at once
  } else if (stops_++ == 0) {
    spdlog::info("worker: draining (finishing the running tasks; signal again to stop them)");
    running_->Drain();
  } else {
    running_->Abort();
  }
}

}  // namespace wavebake::driver
