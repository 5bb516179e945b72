#pragma once
// Runs independent tasks on a few threads, for the single-process driver
// (worker/local_bake.h). The tasks themselves know nothing of it: they are
// the same functions remote workers run (DESIGN.md §2).
#include <functional>

#include "absl/status/status.h"

namespace wavebake {

// Calls task(i) for every i in [0, count) on `threads` threads (at least 1),
// each index exactly once, in no particular order. After the first failure no
// new task starts; the first failure observed is returned once the running
// ones have finished.
absl::Status RunTasks(int count, int threads, const std::function<absl::Status(int)>& task);

}  // namespace wavebake
