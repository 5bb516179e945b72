#include "web/bake_monitor.h"

#include <spdlog/spdlog.h>

#include "web/coordinator_source.h"

namespace wavebake::web {

BakeMonitor::BakeMonitor(std::unique_ptr<MonitorServer> server, std::filesystem::path out)
    : out_(std::move(out)), server_(std::move(server)) {}

void BakeMonitor::Attach(driver::EmbeddedBakeOptions& options) {
  if (!server_) return;
  options.on_started = [this](Coordinator& c, const PlannerOptions& planner) {
    live_ = CoordinatorSource(c, planner);
    server_->SetSource(live_);
  };
  options.on_ending = [this](Coordinator&, const std::string& job_id) {
    std::shared_ptr<JobSource> frozen;
    if (!job_id.empty()) {
      absl::StatusOr<std::shared_ptr<JobSource>> f = FrozenJob(*live_, job_id, out_);
      if (f.ok()) frozen = *std::move(f);
      if (!f.ok()) spdlog::warn("bake: the monitor cannot keep the job: {}", f.status().ToString());
    }
    server_->SetSource(std::move(frozen));  // the coordinator goes next
    live_.reset();
  };
}

}  // namespace wavebake::web
