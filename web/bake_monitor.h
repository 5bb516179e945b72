#pragma once
// The web monitor of an embedded bake (driver/bake/embedded_bake.h, `bake
// --serve`): while the bake runs, the pages show its in-process coordinator;
// once it has ended, a frozen copy of the job whose store is at `out`, which
// the relight view opens.
#include <filesystem>
#include <memory>

#include "driver/bake/embedded_bake.h"
#include "web/job_source.h"
#include "web/monitor_server.h"

namespace wavebake::web {

class BakeMonitor {
 public:
  // A null server: no monitor (Attach does nothing).
  BakeMonitor(std::unique_ptr<MonitorServer> server, std::filesystem::path out);
  explicit operator bool() const { return server_ != nullptr; }
  const MonitorServer& server() const { return *server_; }

  // Hooks the monitor into the bake's coordinator: live while it runs, the
  // frozen job once it ends.
  void Attach(driver::EmbeddedBakeOptions& options);

 private:
  std::filesystem::path out_;
  std::unique_ptr<MonitorServer> server_;
  std::shared_ptr<JobSource> live_;
};

}  // namespace wavebake::web
