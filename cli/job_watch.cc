#include "cli/job_watch.h"

#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "cli/command_error.h"

namespace wavebake::cli {
namespace {

// PHASE_DONE -> "DONE".
std::string PhaseWord(v1::Phase p) { return v1::Phase_Name(p).substr(6); }

bool IsTerminal(v1::Phase p) {
  return p == v1::PHASE_DONE || p == v1::PHASE_FAILED || p == v1::PHASE_CANCELLED;
}

absl::StatusOr<v1::Job> GetJob(const Client& client, const std::string& job_id) {
  v1::JobId id;
  id.set_id(job_id);
  v1::Job job;
  if (grpc::Status s = client.jobs().Get(client.Call().get(), id, &job); !s.ok())
    return FromGrpc(s);
  return job;
}

// Events that deserve a line beside the bar.
void PrintNotable(const v1::JobEvent& e) {
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
      return;
  }
  std::string task;
  if (e.task_kind() != v1::TASK_KIND_UNSPECIFIED)
    task = absl::StrCat(" (", v1::TaskKind_Name(e.task_kind()), " ", e.task_index(), ")");
  std::fprintf(stderr, "\njob %s: %s%s%s%s\n", e.job_id().c_str(), what, task.c_str(),
               e.message().empty() ? "" : ": ", e.message().c_str());
}

// What the streams of one watch have seen: a reconnected stream replays every
// persisted event, and persisted events carry no rate of their own.
struct Seen {
  int64_t seq = 0;
  double rays_per_second = -1;
  double eta_seconds = -1;
  bool ended = false;
};

// One Watch stream, to its end; `progressed`: it delivered something new.
grpc::Status Follow(const Client& client, const std::string& job_id, int tiles, int groups,
                    ProgressReporter* reporter, Seen& seen, bool* progressed) {
  v1::JobId id;
  id.set_id(job_id);
  std::unique_ptr<grpc::ClientContext> ctx = client.Call(0);
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
      event.set_eta_seconds(seen.eta_seconds);
      if (reporter) PrintNotable(event);
    }
    *progressed = true;
    if (reporter && event.phase() != v1::PHASE_QUEUED)
      reporter->Update(ToProgressState(event, tiles, groups));
    seen.ended = seen.ended || IsTerminal(event.phase());
  }
  return reader->Finish();
}

}  // namespace

ProgressState ToProgressState(const v1::JobEvent& e, int tiles, int groups) {
  ProgressState s;
  s.rays = static_cast<uint64_t>(e.rays_traced());
  s.rays_per_second = e.rays_per_second();
  s.eta_seconds = e.eta_seconds();
  switch (e.phase()) {
    case v1::PHASE_BAKING:
      s.phase = "bake tiles";
      s.done = e.tasks_done();
      s.total = tiles;
      break;
    case v1::PHASE_TRANSFORMING:
      s.phase = "transform columns";
      s.done = e.tasks_done() - tiles;
      s.total = groups;
      break;
    case v1::PHASE_FINALIZING:
      s.phase = "finalize";
      s.done = e.tasks_done() - tiles - groups;
      s.total = 1;
      break;
    default:  // queued or ended: the whole job
      s.phase = absl::AsciiStrToLower(PhaseWord(e.phase()));
      s.done = e.tasks_done();
      s.total = e.tasks_total();
  }
  return s;
}

std::string JobOutcome(const v1::Job& job) {
  std::string text = absl::StrCat("job ", job.id(), " ", PhaseWord(job.phase()));
  if (!job.error().empty()) absl::StrAppend(&text, ": ", job.error());
  if (job.phase() == v1::PHASE_DONE) absl::StrAppend(&text, " (store ", job.store_path(), ")");
  return text;
}

absl::StatusOr<v1::Job> WatchJob(const Client& client, const std::string& job_id,
                                 double patience_seconds, bool quiet) {
  absl::StatusOr<v1::Job> job = GetJob(client, job_id);
  if (!job.ok()) return job.status();
  ProgressReporter reporter;
  ProgressReporter* shown = quiet ? nullptr : &reporter;
  Seen seen;
  std::optional<std::chrono::steady_clock::time_point> down_since;
  while (!seen.ended) {
    bool progressed = false;
    const grpc::Status s =
        Follow(client, job_id, job->tiles(), job->groups(), shown, seen, &progressed);
    if (seen.ended) break;
    // A stream ends early when the coordinator goes away (UNAVAILABLE, or OK
    // from one shutting down): wait for it to come back.
    if (!s.ok() && s.error_code() != grpc::StatusCode::UNAVAILABLE) {
      reporter.Finish();
      return FromGrpc(s);
    }
    const auto now = std::chrono::steady_clock::now();
    if (progressed || !down_since) down_since = now;
    if (now - *down_since > std::chrono::duration<double>(patience_seconds)) {
      reporter.Finish();
      return absl::UnavailableError(absl::StrCat("coordinator unreachable for ", patience_seconds,
                                                 " s: ", s.error_message()));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  reporter.Finish();
  return GetJob(client, job_id);
}

}  // namespace wavebake::cli
