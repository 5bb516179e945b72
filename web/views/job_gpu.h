#pragma once
// The job page's relight view on the browser's GPU: a finished job's store
// served as mode=4d of `wavebake view` serves it (web/views/gpu_view_state.h
// ServeColumns: the CSC arrays once, then only the kept lights per frame),
// so the page's rotation, probe and term controls cost no frame request.
// Stores the GPU path cannot draw are refused by name (FailedPrecondition),
// and the page keeps the server's frames: visibility stores (relit through
// the triple product), a plane light domain, a column filter other than
// Haar, mesh layouts (the server draws their vertex colours).
//
//   /api/jobs/ID/gpu/{meta.json,entries.bin,indptr.bin,depth.bin,cells.bin}
//   /api/jobs/ID/gpu/lights?probe=&rotate=&terms=
#include <filesystem>
#include <list>
#include <memory>
#include <mutex>
#include <string>

#include "absl/status/statusor.h"
#include "web/views/gpu_view_state.h"

namespace wavebake::web {

class JobGpu {
 public:
  explicit JobGpu(ProbeCatalogue probes, size_t max_open = 2)
      : lights_(std::move(probes)), max_open_(max_open) {}
  // The store's columns, opened once and kept (least recently used out).
  absl::StatusOr<std::shared_ptr<const ServedColumns>> Open(const std::filesystem::path& store);
  GpuLights& lights() { return lights_; }

 private:
  GpuLights lights_;
  const size_t max_open_;
  std::mutex mu_;
  std::list<std::pair<std::string, std::shared_ptr<const ServedColumns>>> open_;
};

}  // namespace wavebake::web
