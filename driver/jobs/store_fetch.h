#pragma once
// `wavebake fetch` (DESIGN.md §4 ReadStore): a finished store streamed from
// the coordinator into a temporary directory beside the destination, checked,
// then renamed into place — the destination holds a whole, readable store or
// nothing.
#include <filesystem>
#include <string>

#include "absl/status/status.h"
#include "driver/jobs/client.h"

namespace wavebake::driver {

struct FetchSummary {
  int files = 0;
  int64_t bytes = 0;
  int arrays = 0;
};

// `out` must not exist (AlreadyExists naming "--out") and its parent must.
absl::StatusOr<FetchSummary> FetchStore(const Client& client, const std::string& job_id,
                                        const std::filesystem::path& out);

}  // namespace wavebake::driver
