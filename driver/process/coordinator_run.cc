#include "driver/process/coordinator_run.h"

#include <chrono>
#include <thread>

#include "absl/strings/str_cat.h"
#include "storage/files/atomic_file.h"

namespace wavebake::driver {
namespace {

// For tests of shutdown: every plan first waits this long, so a submit is
// deterministically busy when SIGTERM comes.
PlanFn SlowPlanner(PlanFn plan, int64_t delay_ms) {
  if (delay_ms <= 0) return plan;
  return [plan = std::move(plan), delay_ms](const v1::BakeRequest& request) {
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    return plan(request);
  };
}

}  // namespace

absl::StatusOr<CoordinatorRun> StartCoordinator(CoordinatorOptions options,
                                                const std::filesystem::path& address_file,
                                                int64_t test_plan_delay_ms) {
  if (options.store_root.empty()) options.store_root = options.data_dir / "store";
  CoordinatorRun run;
  run.planner = {
      .data_dir = options.data_dir, .store_root = options.store_root, .local_scenes = {}};
  absl::StatusOr<std::unique_ptr<Coordinator>> coordinator =
      Coordinator::Start(options, SlowPlanner(MakeJobPlanner(run.planner), test_plan_delay_ms),
                         MakeJobCleanup(options.store_root));
  if (!coordinator.ok()) return coordinator.status();
  run.coordinator = *std::move(coordinator);
  if (!address_file.empty())
    if (absl::Status s = WriteAddressFile(address_file, run.coordinator->address()); !s.ok())
      return absl::Status(s.code(), absl::StrCat("--address-file: ", s.message()));
  return run;
}

absl::Status WriteAddressFile(const std::filesystem::path& file, const std::string& address) {
  return AtomicWriteText(file, address + "\n");
}

}  // namespace wavebake::driver
