#pragma once
// An update over gRPC (`wavebake submit NEW --update JOB_OR_STORE`,
// worker/tiles/row_reuse.h): a client names the old store by the job that
// baked it, never by a path of this machine. The coordinator turns that name
// into the store's place under the store root (update_from) and the old job's
// scene (update_scene, which the workers load as they load any job's scene:
// the old placement of what moved bounds the rows to rebake).
#include <filesystem>

#include "absl/status/status.h"
#include "coordinator/scheduling/lease_table.h"
#include "wavebake.pb.h"

namespace wavebake {

// Resolves request.update_job ("42", or the output_name of a store under
// store_root) against the jobs of `table`: the job of that id, or the newest
// whose store has that name (a second can exist only once the first's store
// was removed). It must be DONE, baked with keep_staging, still keep its
// staged rows and have every recorded parameter equal to the request's; then
// update_from (relative to store_root) and update_scene are set. Does nothing
// without update_job. Refuses, naming the field: update_scene or update_from
// set by a client beside update_job, an unknown or unfinished job, a store
// baked without keep_staging or since removed, the first parameter that differs.
absl::Status ResolveUpdateJob(const LeaseTable& table, const std::filesystem::path& store_root,
                              v1::BakeRequest& request);

}  // namespace wavebake
