#include "coordinator/service/worker_errors.h"

#include "absl/strings/cord.h"
#include "absl/strings/str_cat.h"
#include "wavebake.pb.h"

namespace wavebake {
namespace {

absl::Status WithReason(absl::Status status, v1::WorkerError::Reason reason) {
  v1::WorkerError error;
  error.set_reason(reason);
  status.SetPayload(
      absl::StrCat("type.googleapis.com/", v1::WorkerError::descriptor()->full_name()),
      absl::Cord(error.SerializeAsString()));
  return status;
}

}  // namespace

absl::Status UnknownWorkerError(int64_t worker_id) {
  return WithReason(absl::NotFoundError(absl::StrCat("worker_id: unknown worker ", worker_id)),
                    v1::WorkerError::UNKNOWN_WORKER);
}

absl::Status ExcludedWorkerError(int64_t worker_id, int consecutive_failures) {
  return WithReason(absl::FailedPreconditionError(
                        absl::StrCat("worker_id: worker ", worker_id, " is excluded after ",
                                     consecutive_failures, " consecutive failures")),
                    v1::WorkerError::WORKER_EXCLUDED);
}

}  // namespace wavebake
