#include "driver/coordinator_run.h"

#include "absl/strings/str_cat.h"
#include "storage/atomic_file.h"

namespace wavebake::driver {

absl::StatusOr<CoordinatorRun> StartCoordinator(CoordinatorOptions options,
                                                const std::filesystem::path& address_file) {
  if (options.store_root.empty()) options.store_root = options.data_dir / "store";
  CoordinatorRun run;
  run.planner = {
      .data_dir = options.data_dir, .store_root = options.store_root, .local_scenes = {}};
  absl::StatusOr<std::unique_ptr<Coordinator>> coordinator =
      Coordinator::Start(options, MakeJobPlanner(run.planner), MakeJobCleanup(options.store_root));
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
