#pragma once
// Following a job to its end (DESIGN.md §4 Watch) across coordinator
// restarts: a reconnected stream replays every persisted event from the
// first, so events already delivered are skipped, and persisted events (which
// carry no rates of their own) get the latest live rays/s and ETA. What to do
// with each event — a progress bar, a web page, a Python iterator — is the
// caller's.
#include <functional>
#include <stop_token>
#include <string>

#include "absl/status/statusor.h"
#include "driver/jobs/client.h"
#include "wavebake.pb.h"

namespace wavebake::driver {

struct WatchOptions {
  // While the coordinator is unavailable (restarting), keep reconnecting for
  // up to this long at a stretch.
  double patience_seconds = 60;
  // Each new event in order: persisted ones once each, live progress ones as
  // they come. Called on the watching thread.
  std::function<void(const v1::JobEvent&)> on_event = {};
  // Once requested, the watch stops (its stream is cancelled) and returns
  // CANCELLED: a Python iterator dropped early, a page closed.
  std::stop_token stop = {};
};

// Streams the job's events until it ends and returns the job as it ended.
// Errors: the RPC's (NOT_FOUND for an unknown job, UNAUTHENTICATED, ...), or
// UNAVAILABLE once the coordinator stayed away past the patience.
absl::StatusOr<v1::Job> WatchJob(const Client& client, const std::string& job_id,
                                 const WatchOptions& options = {});

// A notable event's one-line description ("task failed (BAKE_TILE 3): ...",
// "lease expired ..."), or "" for routine progress and phase changes.
std::string NotableEventText(const v1::JobEvent& event);

}  // namespace wavebake::driver
