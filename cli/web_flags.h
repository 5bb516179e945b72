#pragma once
// The web monitor's flags (web/monitor_server.h), shared by `coordinator
// --http ADDR` and `bake --serve ADDR`: where to listen, where to write the
// bound address (port 0), the probe directory of the relight view.
#include <CLI/CLI.hpp>
#include <atomic>
#include <memory>
#include <string>

#include "web/monitor_server.h"

namespace wavebake::cli {

struct WebFlags {
  std::string flag;                           // --http or --serve
  web::MonitorOptions options{.listen = ""};  // no listen address: no monitor
  std::string address_file, probes;
};

// `listen_flag` is --http or --serve; the others are named after it
// (--http-address-file, ...) except --probes.
void AddWebFlags(CLI::App& cmd, WebFlags& f, const std::string& listen_flag,
                 const std::string& listen_help);

// Starts the monitor (nullptr when no address was given; the caller sets
// the token and TLS files in f.options) and writes its address file; exits
// through Fail on bad flags.
std::unique_ptr<web::MonitorServer> StartMonitor(const std::string& command, WebFlags f,
                                                 std::shared_ptr<web::JobSource> source);

// Tells where the finished job is served, then waits for `stop` (a signal).
void ServeUntil(const std::string& command, const web::MonitorServer& server,
                const std::atomic<bool>& stop);

}  // namespace wavebake::cli
