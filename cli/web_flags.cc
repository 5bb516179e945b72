#include "cli/web_flags.h"

#include <chrono>
#include <cstdio>
#include <thread>

#include "absl/strings/str_cat.h"
#include "cli/command_error.h"
#include "driver/process/coordinator_run.h"

namespace wavebake::cli {

void AddWebFlags(CLI::App& cmd, WebFlags& f, const std::string& listen_flag,
                 const std::string& listen_help) {
  f.flag = listen_flag;
  CLI::Option* listen = cmd.add_option(listen_flag, f.options.listen, listen_help);
  cmd.add_option(listen_flag + "-address-file", f.address_file,
                 "write the web monitor's address (host:port) to this file once serving")
      ->needs(listen);
  cmd.add_option("--probes", f.probes,
                 "directory of .hdr/.exr environments the relight view offers besides the "
                 "built-ins (clients choose by name, never by path)")
      ->needs(listen);
  cmd.add_option(listen_flag + "-pages", f.options.pages_dir,
                 "serve the monitor's pages from this directory (files named as web/static/) "
                 "instead of the built-in copies")
      ->needs(listen);
}

std::unique_ptr<web::MonitorServer> StartMonitor(const std::string& command, WebFlags f,
                                                 std::shared_ptr<web::JobSource> source) {
  if (f.options.listen.empty()) return nullptr;
  if (!f.probes.empty()) {
    absl::StatusOr<web::ProbeCatalogue> probes = web::ProbeCatalogue::Scan(f.probes);
    if (!probes.ok()) Fail(command, probes.status());
    f.options.probes = *std::move(probes);
  }
  absl::StatusOr<std::unique_ptr<web::MonitorServer>> server =
      web::MonitorServer::Start(std::move(f.options), std::move(source));
  if (!server.ok()) Fail(command, server.status());
  if (!f.address_file.empty())
    if (absl::Status s = driver::WriteAddressFile(f.address_file, (*server)->address()); !s.ok())
      Fail(command, absl::StrCat(f.flag, "-address-file: ", s.message()));
  std::fprintf(stderr, "%s: web monitor at %s\n", command.c_str(), (*server)->url().c_str());
  return *std::move(server);
}

void ServeUntil(const std::string& command, const web::MonitorServer& server,
                const std::atomic<bool>& stop) {
  std::fflush(stdout);
  std::fprintf(stderr, "%s: serving the finished bake at %s; Ctrl-C to stop\n", command.c_str(),
               server.url().c_str());
  while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

}  // namespace wavebake::cli
