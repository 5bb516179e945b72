#include "coordinator/service/update_job.h"

#include <limits>
#include <optional>

#include "absl/strings/str_cat.h"
#include "coordinator/scheduling/lease_id.h"
#include "proto/bake_request.h"
#include "storage/store/params_json.h"
#include "storage/store/store_layout.h"

namespace wavebake {
namespace {

absl::Status Bad(const auto&... why) {
  return absl::InvalidArgumentError(absl::StrCat("update_job: ", why...));
}
absl::Status NotReady(const auto&... why) {
  return absl::FailedPreconditionError(absl::StrCat("update_job: ", why...));
}

// The job by id, or the newest whose store is `name` (a failed job may share
// a DONE one's output_name only after that store was removed).
std::optional<JobInfo> FindJob(const LeaseTable& table, const std::string& name) {
  if (const std::optional<int64_t> id = ParseId(name)) {
    absl::StatusOr<JobInfo> info = table.Get(*id);
    if (info.ok()) return *std::move(info);
    return std::nullopt;
  }
  for (JobInfo& info : table.List(std::numeric_limits<int>::max(), /*active_only=*/false))
    if (info.record.store_path == name) return std::move(info);
  return std::nullopt;
}

// The first recorded parameter that differs, as the worker's own check
// (CheckUpdateSource) words it against the store's .zattrs.
absl::Status SameParameters(const v1::BakeRequest& old_request, const v1::BakeRequest& request) {
  absl::StatusOr<BakeParams> before = ToBakeParams(old_request), now = ToBakeParams(request);
  if (!before.ok()) return before.status();
  if (!now.ok()) return now.status();
  const std::string differs = FirstParameterDifference(ToJson(*before), ToJson(*now));
  return differs.empty() ? absl::OkStatus() : Bad(differs);
}

}  // namespace

absl::Status ResolveUpdateJob(const LeaseTable& table, const std::filesystem::path& store_root,
                              v1::BakeRequest& request) {
  if (request.has_update_scene())
    return absl::InvalidArgumentError(
        "update_scene: the coordinator sets it from update_job; a client never does");
  if (request.update_job().empty()) return absl::OkStatus();
  if (!request.update_from().empty())
    return absl::InvalidArgumentError(
        "update_from: the coordinator sets it from update_job; a client never does");
  const std::string& name = request.update_job();
  const std::optional<JobInfo> job = FindJob(table, name);
  if (!job) return Bad("\"", name, "\" is neither a job id nor the store of a job here");
  const std::string what = absl::StrCat("job ", job->record.id, " (", job->record.store_path, ")");
  if (job->record.phase != Phase::kDone)
    return NotReady(what, " is ", PhaseName(job->record.phase),
                    ": an update starts from a finished store");
  v1::BakeRequest old_request;
  if (!old_request.ParseFromString(job->record.request))
    return absl::DataLossError(absl::StrCat("update_job: ", what, ": its request does not parse"));
  if (!old_request.keep_staging())
    return NotReady(what,
                    " kept no staged rows to reuse; bake it with --keep-staging to update "
                    "it later");
  std::error_code ec;
  if (!std::filesystem::is_directory(
          store::Path(store_root / job->record.store_path, store::kStagingTransport), ec))
    return NotReady(what, ": its store or its staged rows are gone from the store root");
  if (absl::Status s = SameParameters(old_request, request); !s.ok()) return s;
  request.set_update_from(job->record.store_path);
  *request.mutable_update_scene() = old_request.scene();
  return absl::OkStatus();
}

}  // namespace wavebake
