#include "driver/jobs/job_watch.h"

#include <chrono>
#include <optional>
#include <stop_token>
#include <thread>

#include "absl/strings/str_cat.h"
#include "driver/jobs/job_query.h"

namespace wavebake::driver {
namespace {

bool IsTerminal(v1::Phase p) {
  return p == v1::PHASE_DONE || p == v1::PHASE_FAILED || p == v1::PHASE_CANCELLED;
}

// What the streams of one watch have seen.
struct Seen {
  int64_t seq = 0;
  double rays_per_second = -1;
  double eta_seconds = -1;
  bool ended = false;
};

// One Watch stream, to its end; `progressed`: it delivered something new.
grpc::Status Follow(const Client& client, const std::string& job_id, const WatchOptions& options,
                    Seen& seen, bool* progressed) {
  v1::JobId id;
  id.set_id(job_id);
  std::unique_ptr<grpc::ClientContext> ctx = client.Call(0);
  std::stop_callback cancel(options.stop, [&ctx] { ctx->TryCancel(); });
  std::unique_ptr<grpc::ClientReader<v1::JobEvent>> reader = client.jobs().Watch(ctx.get(), id);
  v1::JobEvent event;
  while (reader->Read(&event)) {
    if (event.kind() == v1::EVENT_PROGRESS) {
      seen.rays_per_second = event.rays_per_second();
      seen.eta_seconds = event.eta_seconds();
    } else {
      if (event.seq() <= seen.seq) continue;
      seen.seq = event.seq();
      event.set_rays_per_second(seen.rays_per_second);
      // An ended job's event keeps its own ETA (0 when DONE, else unknown).
      if (!IsTerminal(event.phase())) event.set_eta_seconds(seen.eta_seconds);
    }
    *progressed = true;
    if (options.on_event) options.on_event(event);
    seen.ended = seen.ended || IsTerminal(event.phase());
  }
  return reader->Finish();
}

}  // namespace

std::string NotableEventText(const v1::JobEvent& e) {
  const char* what = nullptr;
  switch (e.kind()) {
    case v1::EVENT_TASK_FAILED:
      what = "task failed";
      break;
    case v1::EVENT_LEASE_EXPIRED:
      what = "lease expired";
      break;
    case v1::EVENT_WORKER_EXCLUDED:
      what = "worker excluded";
      break;
    case v1::EVENT_RESUMED:
      what = "coordinator restarted; job resumed";
      break;
    default:
      return "";
  }
  std::string text = absl::StrCat("job ", e.job_id(), ": ", what);
  if (e.task_kind() != v1::TASK_KIND_UNSPECIFIED)
    absl::StrAppend(&text, " (", v1::TaskKind_Name(e.task_kind()), " ", e.task_index(), ")");
  if (!e.message().empty()) absl::StrAppend(&text, ": ", e.message());
  return text;
}

absl::StatusOr<v1::Job> WatchJob(const Client& client, const std::string& job_id,
                                 const WatchOptions& options) {
  absl::StatusOr<v1::Job> job = GetJob(client, job_id);
  if (!job.ok()) return job.status();
  Seen seen;
  // Until a progress event says otherwise, the coordinator's rate: the
  // events of a job that has ended (replayed, with no progress among them)
  // carry its final rays / (finished - started), not rays over the few
  // milliseconds this watch has run.
  seen.rays_per_second = job->rays_per_second() > 0 ? job->rays_per_second() : -1;
  std::optional<std::chrono::steady_clock::time_point> down_since;
  while (!seen.ended) {
    bool progressed = false;
    const grpc::Status s = Follow(client, job_id, options, seen, &progressed);
    if (seen.ended) break;
    if (options.stop.stop_requested()) return absl::CancelledError("watch stopped");
    // A stream ends early when the coordinator goes away (UNAVAILABLE, or OK
    // from one shutting down): wait for it to come back.
    if (!s.ok() && s.error_code() != grpc::StatusCode::UNAVAILABLE) return FromGrpc(s);
    const auto now = std::chrono::steady_clock::now();
    if (progressed || !down_since) down_since = now;
    if (now - *down_since > std::chrono::duration<double>(options.patience_seconds)) {
      return absl::UnavailableError(absl::StrCat(
          "coordinator unreachable for ", options.patience_seconds, " s: ", s.error_message()));
    }
    for (int i = 0; i < 5 && !options.stop.stop_requested(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return GetJob(client, job_id);
}

}  // namespace wavebake::driver
