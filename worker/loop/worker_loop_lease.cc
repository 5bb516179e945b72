// WorkerLoop's lease threads: the threads that are between tasks report
// their results and lease their next tasks together. Each sits down in the
// next round; one of them (the first to find no round in flight) makes the
// LeaseBatch call for everyone seated and hands a task to each it can, the
// others wait for that. A worker whose tasks finish together pays one call
// for all its threads; one whose threads finish apart still pays one call
// per task (result and next lease together) instead of two.
#include <grpcpp/client_context.h>
#include <spdlog/spdlog.h>

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "worker/loop/task_buffer.h"
#include "worker/loop/worker_loop.h"

namespace wavebake {

void WorkerLoop::LeaseLoop() {
  std::optional<Finished> finished;  // goes with the next LeaseBatch
  for (int attempt = 0;;) {
    bool draining, batch;
    {
      std::lock_guard lock(mu_);
      draining = draining_;
      batch = batch_leases_;
    }
    if (finished && (draining || !batch)) {  // no next lease: report it on its own
      Report(finished->task, finished->outcome);
      finished.reset();
    }
    if (draining) return;
    Seat seat;
    seat.finished = std::move(finished);
    finished.reset();
    if (batch) {
      TakeSeat(seat);
    } else {
      LeaseSingle(seat);
    }
    finished = std::move(seat.finished);
    if (seat.status.ok()) {
      if (attempt > 0) TlsWorks();
      attempt = 0;
      finished.reset();  // reported
      if (seat.task) {
        finished = RunLeased(*seat.task);
      } else {
        ReleaseTaskBuffer();  // idle: the last task's buffer is not kept for the next job
        SleepUnlessDraining(std::max<int64_t>(1, seat.wait_ms));
      }
      continue;
    }
    if (batch && seat.status.error_code() == grpc::StatusCode::UNIMPLEMENTED) {
      std::lock_guard lock(mu_);
      if (batch_leases_)
        spdlog::info("worker {}: coordinator without LeaseBatch; one task per Lease",
                     seat.worker_id);
      batch_leases_ = false;
      continue;
    }
    if (finished && std::chrono::steady_clock::now() - finished->since > kReportPatience) {
      // The lease's expiry gives the task to another worker.
      spdlog::warn("worker {}: cannot report job {} task {}: {}", seat.worker_id,
                   finished->task.job_id(), finished->task.lease_id(), seat.status.error_message());
      finished.reset();
    }
    if (absl::Status r = Recover(seat.status, seat.worker_id, attempt++); !r.ok()) {
      return SetFatal(r);
    }
  }
}

void WorkerLoop::TakeSeat(Seat& seat) {
  std::unique_lock lock(mu_);
  seats_.push_back(&seat);
  seats_cv_.wait(lock, [&] { return seat.served || !leading_; });
  if (seat.served) return;
  // No round in flight and this seat is still waiting: lead the next round,
  // which takes everyone seated by now, this seat too.
  leading_ = true;
  std::vector<Seat*> round;
  round.swap(seats_);
  lock.unlock();
  ServeRound(round);
  lock.lock();
  leading_ = false;
  seats_cv_.notify_all();
}

void WorkerLoop::ServeRound(const std::vector<Seat*>& round) {
  const std::string id = worker_id();
  bool draining;
  {
    std::lock_guard lock(mu_);
    draining = draining_;
  }
  v1::LeaseBatchRequest request;
  request.set_worker_id(id);
  request.set_max_tasks(draining ? 0 : static_cast<int>(round.size()));
  for (const Seat* seat : round) {
    if (!seat->finished) continue;
    const TaskOutcome& o = seat->finished->outcome;
    v1::TaskResult* r = request.add_completed();
    r->set_worker_id(id);
    r->set_lease_id(seat->finished->task.lease_id());
    r->set_rays_traced(o.rays_traced);
    r->set_bytes_written(o.bytes_written);
    r->set_stats_json(o.stats_json);
  }
  v1::LeaseBatchReply reply;
  const bool idle = request.max_tasks() == 0 && request.completed_size() == 0;
  const grpc::Status status =
      idle ? grpc::Status::OK : stub_->LeaseBatch(Context().get(), request, &reply);
  std::lock_guard lock(mu_);
  int result = 0, task = 0;
  for (Seat* seat : round) {
    seat->served = true;
    seat->status = status;
    seat->worker_id = id;
    if (!status.ok()) continue;
    if (seat->finished) {
      const bool accepted = result < reply.accepted_size() && reply.accepted(result);
      ++result;
      if (accepted) {
        ++counters_.completed;
        counters_.rays_traced += seat->finished->outcome.rays_traced;
        counters_.bytes_written += seat->finished->outcome.bytes_written;
      }
    }
    if (task < reply.tasks_size()) {
      seat->task = reply.tasks(task++);
    } else {
      seat->wait_ms = reply.wait_ms();
    }
  }
}

void WorkerLoop::LeaseSingle(Seat& seat) {
  seat.worker_id = worker_id();
  v1::LeaseRequest request;
  request.set_worker_id(seat.worker_id);
  v1::LeaseReply reply;
  seat.status = stub_->Lease(Context().get(), request, &reply);
  if (!seat.status.ok()) return;
  if (reply.has_task()) {
    seat.task = reply.task();
  } else {
    seat.wait_ms = reply.wait_ms();
  }
}

}  // namespace wavebake
