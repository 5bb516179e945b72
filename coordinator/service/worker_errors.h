#pragma once
// The refusals a worker must act on (proto WorkerError): absl errors that
// carry their reason as a payload under WorkerError's type URL, which
// ToGrpc (coordinator/service/proto_convert.h) sends as status details. The worker
// reads the reason, so the message's wording is free to change.
#include <cstdint>

#include "absl/status/status.h"

namespace wavebake {

// NOT_FOUND, reason UNKNOWN_WORKER: register again.
absl::Status UnknownWorkerError(int64_t worker_id);
// FAILED_PRECONDITION, reason WORKER_EXCLUDED: the worker stops.
absl::Status ExcludedWorkerError(int64_t worker_id, int consecutive_failures);

}  // namespace wavebake
