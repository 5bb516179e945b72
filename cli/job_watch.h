#pragma once
// Following a job to its end (DESIGN.md §4 Watch, §5 "Long work shows a
// progress bar on a terminal and plain progress lines otherwise"): the job's
// events drive cli/progress.h with the coordinator's own rays/s and ETA, and
// the events worth a line of their own (failures, expired leases, restarts)
// are printed as they come.
#include <string>

#include "absl/status/statusor.h"
#include "cli/client.h"
#include "cli/progress.h"
#include "wavebake.pb.h"

namespace wavebake::cli {

// What cli/progress.h shows for an event of a job with `tiles` and `groups`:
// the phase's own tasks done out of its total.
ProgressState ToProgressState(const v1::JobEvent& event, int tiles, int groups);

// Streams the job's events until it ends and returns the job as it ended.
// While the coordinator is unavailable (restarting) it reconnects, for up to
// `patience_seconds` at a stretch. Errors: the RPC's (NOT_FOUND for an
// unknown job, UNAUTHENTICATED, ...).
// quiet: draw nothing (the events are still followed).
absl::StatusOr<v1::Job> WatchJob(const Client& client, const std::string& job_id,
                                 double patience_seconds = 60, bool quiet = false);

// "job 3 DONE", "job 3 FAILED: <error>" ...
std::string JobOutcome(const v1::Job& job);

}  // namespace wavebake::cli
