#pragma once
// A coordinator process (DESIGN.md §4): the job service and the work queue
// over a data directory, with the job planner and the cleanup of
// coordinator/, its address written for scripts. The command line adds the
// web monitor (web/coordinator_source.h) and waits for a signal
// (driver/process/signal_watcher.h), as it does for driver/process/worker_run.h.
#include <cstdint>
#include <filesystem>
#include <memory>

#include "absl/status/statusor.h"
#include "coordinator/service/coordinator.h"
#include "coordinator/service/job_planner.h"

namespace wavebake::driver {

struct CoordinatorRun {
  std::unique_ptr<Coordinator> coordinator;
  PlannerOptions planner;  // what the monitor's job source plans with
};

// options.store_root defaults to DATA/store. address_file (if not empty)
// gets "host:port\n" once serving (for scripts that listen on port 0),
// atomically. Errors: Coordinator::Start's; the address file's, naming
// --address-file. test_plan_delay_ms > 0 (a hidden flag for tests of
// shutdown) makes every plan wait that long first.
absl::StatusOr<CoordinatorRun> StartCoordinator(CoordinatorOptions options,
                                                const std::filesystem::path& address_file,
                                                int64_t test_plan_delay_ms = 0);

// `address` and a newline written whole (rename) to `file`: a script polling
// for the file never reads half an address.
absl::Status WriteAddressFile(const std::filesystem::path& file, const std::string& address);

}  // namespace wavebake::driver
