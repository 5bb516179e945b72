#pragma once
// The web monitor (DESIGN.md §4 "The coordinator also serves HTTP"): pages
// of jobs with live progress and cancel, a job's timeline, store statistics
// and the interactive relight view, `/metrics` (Prometheus text format) and
// `/healthz`, over HTTP or HTTPS (cpp-httplib), behind the coordinator's
// bearer token. Served by `wavebake coordinator --http ADDR` and `wavebake
// bake --serve ADDR`. /healthz stays open, like gRPC health checking, so
// probes need no secret; everything else answers 401 without the token.
// Served by its own accept path (web/http/http_gate.h), one request per
// connection, so that no client holds a serving thread while it sends.
#include <filesystem>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "web/job_source.h"
#include "web/views/probe_catalogue.h"

struct ssl_ctx_st;

namespace httplib {
class Server;
}

namespace wavebake::web {

struct RouteContext;  // web/routes.h
class HttpGate;       // web/http/http_gate.h

struct MonitorOptions {
  std::string listen = "127.0.0.1:0";           // host:port; port 0 picks a free one
  std::string token{};                          // empty: no authentication
  std::filesystem::path tls_cert{}, tls_key{};  // both (HTTPS) or neither (PEM)
  ProbeCatalogue probes{};
  // Serve the pages from this directory instead of the copies built into
  // the binary (the same file names only), to work on them without a rebuild.
  std::filesystem::path pages_dir{};
};

class MonitorServer {
 public:
  // Binds and serves on threads of its own. Errors: an address it cannot
  // listen on (named as `listen`), half of a TLS pair, unreadable PEM files.
  static absl::StatusOr<std::unique_ptr<MonitorServer>> Start(MonitorOptions options,
                                                              std::shared_ptr<JobSource> source);
  ~MonitorServer();  // Stop()

  // Replaces what the pages show; returns once no request reads the old source.
  void SetSource(std::shared_ptr<JobSource> source) { source_.Set(std::move(source)); }
  std::string address() const;  // host:port
  std::string url() const;      // http(s)://host:port/
  // Ends open event streams, stops accepting, joins the serving threads.
  void Stop();

 private:
  MonitorServer();
  MonitorOptions options_;
  SourceSlot source_;
  std::unique_ptr<RouteContext> context_;
  std::unique_ptr<httplib::Server> server_;  // the routes; the gate serves them
  std::unique_ptr<ssl_ctx_st, void (*)(ssl_ctx_st*)> ssl_ctx_{nullptr, nullptr};
  std::unique_ptr<HttpGate> gate_;
  int port_ = 0;
};

}  // namespace wavebake::web
