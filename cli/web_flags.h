#pragma once
// The web monitor's flags (web/monitor_server.h), shared by `coordinator
// --http ADDR` and `bake --serve ADDR`: where to listen, where to write the
// bound address (port 0), the probe directory of the relight view.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <string>

#include "web/monitor_server.h"

namespace wavebake::cli {

struct WebFlags {
  std::string flag;    // --http or --serve
  std::string listen;  // empty: no monitor
  std::string address_file;
  std::string probes;
  std::string pages_dir;
};

// `listen_flag` is --http or --serve; the others are named after it
// (--http-address-file, ...) except --probes.
void AddWebFlags(CLI::App& cmd, WebFlags& f, const std::string& listen_flag,
                 const std::string& listen_help);

// Starts the monitor (nullptr when no address was given) and writes its
// address file; exits through Fail on bad flags.
std::unique_ptr<web::MonitorServer> StartMonitor(const std::string& command, const WebFlags& f,
                                                 const std::string& token,
                                                 const std::filesystem::path& tls_cert,
                                                 const std::filesystem::path& tls_key,
                                                 std::shared_ptr<web::JobSource> source);

}  // namespace wavebake::cli
