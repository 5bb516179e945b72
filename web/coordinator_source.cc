#include "web/coordinator_source.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <utility>

#include "absl/strings/str_cat.h"
#include "coordinator/scheduling/lease_id.h"
#include "coordinator/service/proto_convert.h"

namespace wavebake::web {
namespace {

absl::StatusOr<int64_t> JobNumber(const std::string& id) {
  std::optional<int64_t> n = ParseId(id);
  if (!n) return absl::InvalidArgumentError(absl::StrCat("job: \"", id, "\" is not a job id"));
  return *n;
}

v1::Job ToJob(const JobInfo& info) {
  v1::Job job;
  ToProto(info, &job);
  return job;
}

absl::Status NotDone(const v1::Job& job) {
  return absl::FailedPreconditionError(absl::StrCat(
      "job ", job.id(), " is ", v1::Phase_Name(job.phase()).substr(6), ": no store yet"));
}

class LiveSource final : public JobSource {
 public:
  LiveSource(Coordinator& c, PlannerOptions planner) : c_(c), planner_(std::move(planner)) {
    // Always, unlike CoordinatorOptions::hide_paths: whoever reaches the
    // monitor over HTTP need not be the user of this machine.
    paths_.Hide(c.options().data_dir, "<data dir>");
    paths_.Hide(c.options().store_root, "<store root>");
  }

  absl::StatusOr<std::vector<v1::Job>> ListJobs(int limit) const override {
    std::vector<v1::Job> jobs;
    for (const JobInfo& info : c_.table().List(limit, false)) jobs.push_back(ToJob(info));
    return jobs;
  }
  absl::StatusOr<v1::Job> GetJob(const std::string& id) const override {
    absl::StatusOr<int64_t> n = JobNumber(id);
    if (!n.ok()) return n.status();
    absl::StatusOr<JobInfo> info = c_.table().Get(*n);
    if (!info.ok()) return info.status();
    return ToJob(*info);
  }
  absl::StatusOr<v1::Job> CancelJob(const std::string& id) override {
    absl::StatusOr<int64_t> n = JobNumber(id);
    if (!n.ok()) return n.status();
    absl::StatusOr<JobInfo> info = c_.table().Cancel(*n);
    if (!info.ok()) return info.status();
    return ToJob(*info);
  }
  absl::StatusOr<std::vector<v1::JobEvent>> JobEvents(const std::string& id,
                                                      int limit) const override {
    absl::StatusOr<int64_t> n = JobNumber(id);
    if (!n.ok()) return n.status();
    absl::StatusOr<JobInfo> info = c_.table().Get(*n);
    if (!info.ok()) return info.status();
    std::vector<v1::JobEvent> out;
    int64_t after = 0;
    while (static_cast<int>(out.size()) < limit) {
      const int page = std::min(1000, limit - static_cast<int>(out.size()));
      absl::StatusOr<std::vector<EventRecord>> events = c_.table().ReadEvents(*n, after, page);
      if (!events.ok()) return events.status();
      for (const EventRecord& e : *events) ToProto(e, info->record, &out.emplace_back());
      if (static_cast<int>(events->size()) < page) break;
      after = events->back().seq;
    }
    return out;
  }
  absl::StatusOr<std::filesystem::path> StoreDir(const std::string& id) const override {
    absl::StatusOr<v1::Job> job = GetJob(id);
    if (!job.ok()) return job.status();
    if (job->phase() != v1::PHASE_DONE) return NotDone(*job);
    return c_.options().store_root / job->store_path();
  }
  absl::StatusOr<Scene> JobScene(const std::string& id) const override {
    absl::StatusOr<v1::Job> job = GetJob(id);
    if (!job.ok()) return job.status();
    return LoadRequestScene(job->request(), planner_);
  }
  SchedulerSnapshot Metrics(int job_limit) const override { return c_.table().Metrics(job_limit); }
  uint64_t WaitForChange(uint64_t seen, int64_t timeout_ms) const override {
    return c_.table().WaitForChange(seen, timeout_ms);
  }
  const ClientPaths& client_paths() const override { return paths_; }

 private:
  Coordinator& c_;
  const PlannerOptions planner_;
  ClientPaths paths_;
};

class FrozenSource final : public JobSource {
 public:
  FrozenSource(v1::Job job, std::vector<v1::JobEvent> events, SchedulerSnapshot metrics,
               absl::StatusOr<Scene> scene, std::filesystem::path store_dir, ClientPaths paths)
      : job_(std::move(job)),
        events_(std::move(events)),
        metrics_(std::move(metrics)),
        scene_(std::move(scene)),
        store_dir_(std::move(store_dir)),
        paths_(std::move(paths)) {
    paths_.Hide(store_dir_.parent_path(), "<store root>");
  }

  absl::StatusOr<std::vector<v1::Job>> ListJobs(int limit) const override {
    if (limit < 1) return std::vector<v1::Job>{};
    return std::vector<v1::Job>{job_};
  }
  absl::StatusOr<v1::Job> GetJob(const std::string& id) const override {
    if (id != job_.id()) return absl::NotFoundError(absl::StrCat("job ", id, " not found"));
    return job_;
  }
  absl::StatusOr<v1::Job> CancelJob(const std::string& id) override {
    absl::StatusOr<v1::Job> job = GetJob(id);
    if (!job.ok()) return job.status();
    return absl::FailedPreconditionError(
        absl::StrCat("job ", id, " already ended ", v1::Phase_Name(job_.phase()).substr(6)));
  }
  absl::StatusOr<std::vector<v1::JobEvent>> JobEvents(const std::string& id,
                                                      int limit) const override {
    if (absl::StatusOr<v1::Job> job = GetJob(id); !job.ok()) return job.status();
    const size_t n = std::min(events_.size(), static_cast<size_t>(std::max(limit, 0)));
    return std::vector<v1::JobEvent>(events_.begin(), events_.begin() + n);
  }
  absl::StatusOr<std::filesystem::path> StoreDir(const std::string& id) const override {
    if (absl::StatusOr<v1::Job> job = GetJob(id); !job.ok()) return job.status();
    if (job_.phase() != v1::PHASE_DONE) return NotDone(job_);
    return store_dir_;
  }
  absl::StatusOr<Scene> JobScene(const std::string& id) const override {
    if (absl::StatusOr<v1::Job> job = GetJob(id); !job.ok()) return job.status();
    return scene_;
  }
  SchedulerSnapshot Metrics(int) const override { return metrics_; }
  uint64_t WaitForChange(uint64_t, int64_t timeout_ms) const override {
    // Nothing changes any more: wait the whole timeout (callers bound it).
    std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
    return 0;
  }
  const ClientPaths& client_paths() const override { return paths_; }

 private:
  const v1::Job job_;
  const std::vector<v1::JobEvent> events_;
  const SchedulerSnapshot metrics_;
  const absl::StatusOr<Scene> scene_;
  const std::filesystem::path store_dir_;
  ClientPaths paths_;
};

}  // namespace

std::shared_ptr<JobSource> CoordinatorSource(Coordinator& coordinator, PlannerOptions planner) {
  return std::make_shared<LiveSource>(coordinator, std::move(planner));
}

absl::StatusOr<std::shared_ptr<JobSource>> FrozenJob(const JobSource& live, const std::string& id,
                                                     std::filesystem::path store_dir) {
  absl::StatusOr<v1::Job> job = live.GetJob(id);
  if (!job.ok()) return job.status();
  constexpr int kMaxEvents = 100'000;
  absl::StatusOr<std::vector<v1::JobEvent>> events = live.JobEvents(id, kMaxEvents);
  if (!events.ok()) return events.status();
  return std::make_shared<FrozenSource>(*std::move(job), *std::move(events), live.Metrics(1),
                                        live.JobScene(id), std::move(store_dir),
                                        live.client_paths());
}

}  // namespace wavebake::web
