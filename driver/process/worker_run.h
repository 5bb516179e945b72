#pragma once
// A worker process (DESIGN.md §4): one WorkerLoop run to its end, stopped by
// signals in two steps — the first Stop() drains (no new task; the running
// ones finish and are reported), a second stops the running tasks too
// (reported as failed). A Stop() before the loop exists drains it at once.
#include <memory>
#include <mutex>

#include "absl/status/status.h"
#include "worker/loop/worker_loop.h"

namespace wavebake::driver {

class WorkerRun {
 public:
  absl::Status Run(std::shared_ptr<grpc::ChannelInterface> channel, WorkerOptions options);
  void Stop();  // from any thread (a signal watcher's)

 private:
  std::mutex mu_;
  WorkerLoop* running_ = nullptr;
  int stops_ = 0;
};

}  // namespace wavebake::driver
