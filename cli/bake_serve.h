#pragma once
// `wavebake bake --serve ADDR`: the web monitor of the embedded bake
// (driver/embedded_bake.h). While the bake runs the pages show its
// in-process coordinator; once it has ended, a frozen copy of the job whose
// store is at --out, which the relight view opens — served until SIGINT.
#include <atomic>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/web_flags.h"
#include "driver/embedded_bake.h"
#include "web/job_source.h"

namespace wavebake::cli {

class BakeMonitor {
 public:
  // No monitor unless f.listen is set. token_file: --token-file (may be empty).
  BakeMonitor(const WebFlags& f, const std::string& token_file, std::filesystem::path out);
  explicit operator bool() const { return server_ != nullptr; }

  // Hooks the monitor into the bake's coordinator.
  void Attach(driver::EmbeddedBakeOptions& options);
  // Keeps serving the finished bake until `stop` rises (a signal).
  void ServeUntil(const std::atomic<bool>& stop) const;

 private:
  std::filesystem::path out_;
  std::unique_ptr<web::MonitorServer> server_;
  std::shared_ptr<web::JobSource> live_;
};

}  // namespace wavebake::cli
