#pragma once
// What the web monitor shows and where it comes from: the jobs of a
// coordinator (DESIGN.md §4 Get, List, Cancel, the persisted events), its
// scheduler metrics, a finished job's store directory and its scene. The
// coordinator process serves its own (web/coordinator_source.h); `wavebake
// bake --serve` serves the embedded coordinator's while it runs and a frozen
// copy of the one job afterwards, when that coordinator is gone.
#include <filesystem>
#include <memory>
#include <shared_mutex>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "coordinator/scheduling/scheduler_metrics.h"
#include "coordinator/service/client_paths.h"
#include "core/scene/scene.h"
#include "wavebake.pb.h"

namespace wavebake::web {

class JobSource {
 public:
  virtual ~JobSource() = default;
  virtual absl::StatusOr<std::vector<v1::Job>> ListJobs(int limit) const = 0;
  virtual absl::StatusOr<v1::Job> GetJob(const std::string& id) const = 0;
  virtual absl::StatusOr<v1::Job> CancelJob(const std::string& id) = 0;
  // The job's persisted events from the first, at most `limit`.
  virtual absl::StatusOr<std::vector<v1::JobEvent>> JobEvents(const std::string& id,
                                                              int limit) const = 0;
  // Where a DONE job's store is (FAILED_PRECONDITION for any other job).
  virtual absl::StatusOr<std::filesystem::path> StoreDir(const std::string& id) const = 0;
  // The job's scene as its bake loaded it (for pictures of mesh stores).
  virtual absl::StatusOr<Scene> JobScene(const std::string& id) const = 0;
  virtual SchedulerSnapshot Metrics(int job_limit) const = 0;
  // Blocks until something may have changed or timeout_ms passes; returns a
  // token that differs from `seen` after a change.
  virtual uint64_t WaitForChange(uint64_t seen, int64_t timeout_ms) const = 0;
  // The server directories an HTTP client must not see (DESIGN.md §4, as
  // the JobService hides them): every body the monitor sends passes it.
  virtual const ClientPaths& client_paths() const {
    static const ClientPaths kNone;
    return kNone;
  }
};

// The source the server reads, replaceable while it serves: Set() returns
// once no request uses the previous source any more, so its owner may then
// destroy what it reads (the embedded coordinator).
class SourceSlot {
 public:
  void Set(std::shared_ptr<JobSource> source);
  // A source held by a request: the slot's Set() waits for it to go.
  class Use {
   public:
    JobSource* get() const { return source_.get(); }
    JobSource* operator->() const { return source_.get(); }
    explicit operator bool() const { return source_ != nullptr; }

   private:
    friend class SourceSlot;
    Use(std::shared_lock<std::shared_mutex> lock, std::shared_ptr<JobSource> source)
        : lock_(std::move(lock)), source_(std::move(source)) {}
    std::shared_lock<std::shared_mutex> lock_;
    std::shared_ptr<JobSource> source_;
  };
  // Null inside when no source was set yet. Hold it only for one request's
  // reading and bounded waits (WaitForChange of a second), never across a
  // write to the client.
  Use Get() const;

 private:
  mutable std::shared_mutex mu_;
  std::shared_ptr<JobSource> source_;
};

}  // namespace wavebake::web
