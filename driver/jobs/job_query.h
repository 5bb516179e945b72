#pragma once
// One-shot questions and orders to a running coordinator (DESIGN.md §4 Get,
// List, Cancel), with absl errors in place of gRPC ones.
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "driver/jobs/client.h"
#include "wavebake.pb.h"

namespace wavebake::driver {

// NOT_FOUND for an unknown job; INVALID_ARGUMENT for an id that is not one.
absl::StatusOr<v1::Job> GetJob(const Client& client, const std::string& job_id);

// The newest `limit` jobs, newest first; only those not ended if active_only.
absl::StatusOr<std::vector<v1::Job>> ListJobs(const Client& client, int limit, bool active_only);

// The job as cancelled; FAILED_PRECONDITION when it already ended otherwise.
absl::StatusOr<v1::Job> CancelJob(const Client& client, const std::string& job_id);

// "job 3 DONE (store job-3.wbk)", "job 3 FAILED: <error>" ...
std::string JobOutcome(const v1::Job& job);

}  // namespace wavebake::driver
