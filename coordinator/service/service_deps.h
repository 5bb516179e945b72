#pragma once
// What the two gRPC services share: the scheduler, the scenes, auth, the
// planner, and where stores live. Owned by the Coordinator.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>

#include "coordinator/scheduling/job_types.h"
#include "coordinator/scheduling/lease_table.h"
#include "coordinator/service/auth.h"
#include "coordinator/service/client_paths.h"
#include "coordinator/state/scene_store.h"

namespace wavebake {

struct ServiceDeps {
  LeaseTable* table = nullptr;
  SceneStore* scenes = nullptr;
  const TokenAuth* auth = nullptr;
  PlanFn plan;
  std::filesystem::path store_root;
  std::string store_root_id;    // of store_root's marker (storage/store/store_root_marker.h)
  int64_t wait_ms = 500;        // LeaseReply.wait_ms when no task is ready
  int64_t watch_poll_ms = 500;  // Watch: longest wait between checks / progress events
  int chunk_bytes = 1 << 20;    // ReadStore / FetchScene chunk size
  const std::atomic<bool>* stopping = nullptr;  // ends Watch streams at shutdown
  ClientPaths client_paths;  // applied to every message a JobService client receives
  // Rewrite the paths in workers' failure reasons before they are stored
  // (coordinator/service/worker_paths.h); with client_paths, off for the embedded bake.
  bool hide_worker_paths = false;
};

}  // namespace wavebake
