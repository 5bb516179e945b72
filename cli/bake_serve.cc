#include "cli/bake_serve.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "cli/command_error.h"
#include "driver/client.h"
#include "web/coordinator_source.h"

namespace wavebake::cli {

BakeMonitor::BakeMonitor(const WebFlags& f, const std::string& token_file,
                         std::filesystem::path out)
    : out_(std::move(out)) {
  if (f.listen.empty()) return;
  std::string token;
  if (!token_file.empty()) {
    absl::StatusOr<std::string> t = driver::ReadTokenFile(token_file);
    if (!t.ok()) Fail("bake", t.status());
    token = *t;
  }
  server_ = StartMonitor("bake", f, token, {}, {}, nullptr);
  std::fprintf(stderr, "bake: web monitor at %s\n", server_->url().c_str());
}

void BakeMonitor::Attach(driver::EmbeddedBakeOptions& options) {
  if (!server_) return;
  options.on_started = [this](Coordinator& c, const PlannerOptions& planner) {
    live_ = web::CoordinatorSource(c, planner);
    server_->SetSource(live_);
  };
  options.on_ending = [this](Coordinator&, const std::string& job_id) {
    std::shared_ptr<web::JobSource> frozen;
    if (!job_id.empty()) {
      absl::StatusOr<std::shared_ptr<web::JobSource>> f = web::FrozenJob(*live_, job_id, out_);
      if (f.ok()) frozen = *std::move(f);
      if (!f.ok()) spdlog::warn("bake: the monitor cannot keep the job: {}", f.status().ToString());
    }
    server_->SetSource(std::move(frozen));  // the coordinator goes next
    live_.reset();
  };
}

void BakeMonitor::ServeUntil(const std::atomic<bool>& stop) const {
  if (!server_) return;
  std::fprintf(stderr, "bake: serving the finished bake at %s; Ctrl-C to stop\n",
               server_->url().c_str());
  while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

}  // namespace wavebake::cli
