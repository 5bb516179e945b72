#include "web/monitor_server.h"

#include <spdlog/spdlog.h>

#include <system_error>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "web/routes.h"

namespace wavebake::web {
namespace {

// Long-lived event streams hold a thread each; relight frames want a few.
constexpr size_t kServerThreads = 16;

// Paths reachable without the token: the probe endpoint and the login page.
bool IsOpenPath(const std::string& path) {
  return path == "/healthz" || path == "/login" || path == "/static/monitor.css";
}

absl::StatusOr<std::pair<std::string, int>> SplitHostPort(const std::string& listen) {
  const size_t colon = listen.rfind(':');
  int port = -1;
  if (colon == std::string::npos || colon == 0 ||
      !absl::SimpleAtoi(listen.substr(colon + 1), &port) || port < 0 || port > 65535) {
    return absl::InvalidArgumentError(
        absl::StrCat("listen: \"", listen, "\" is not host:port (port 0: any free)"));
  }
  std::string host = listen.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']')
    host = host.substr(1, host.size() - 2);
  return std::make_pair(host, port);
}

absl::Status CheckReadable(const std::filesystem::path& p, const char* field) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(p, ec)) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat(field, ": cannot read ", p.string()));
}

}  // namespace

MonitorServer::MonitorServer() = default;

absl::StatusOr<std::unique_ptr<MonitorServer>> MonitorServer::Start(
    MonitorOptions options, std::shared_ptr<JobSource> source) {
  absl::StatusOr<std::pair<std::string, int>> host_port = SplitHostPort(options.listen);
  if (!host_port.ok()) return host_port.status();
  const bool tls = !options.tls_cert.empty();
  if (tls != !options.tls_key.empty())
    return absl::InvalidArgumentError("tls_cert/tls_key: give both or neither");
  std::unique_ptr<MonitorServer> m(new MonitorServer());
  if (tls) {
    if (absl::Status s = CheckReadable(options.tls_cert, "tls_cert"); !s.ok()) return s;
    if (absl::Status s = CheckReadable(options.tls_key, "tls_key"); !s.ok()) return s;
    auto ssl =
        std::make_unique<httplib::SSLServer>(options.tls_cert.c_str(), options.tls_key.c_str());
    if (!ssl->is_valid())
      return absl::InvalidArgumentError(
          absl::StrCat("tls_cert/tls_key: ", options.tls_cert.string(), " and ",
                       options.tls_key.string(), " are not a PEM certificate and its key"));
    m->server_ = std::move(ssl);
  } else {
    m->server_ = std::make_unique<httplib::Server>();
  }
  m->options_ = options;
  m->source_.Set(std::move(source));
  m->context_ = std::make_unique<RouteContext>(&m->source_, options.token, options.probes,
                                               options.pages_dir, tls);

  httplib::Server& server = *m->server_;
  // httplib owns and deletes the queue it is given.
  server.new_task_queue = [] { return new httplib::ThreadPool(kServerThreads); };
  server.set_keep_alive_max_count(1000);  // the relight view asks frame after frame
  server.set_tcp_nodelay(true);           // a frame is headers then body: no Nagle wait
  server.set_read_timeout(10);
  server.set_write_timeout(10);
  server.set_payload_max_length(1 << 16);  // only small forms and queries come in
  RouteContext& ctx = *m->context_;
  server.set_pre_routing_handler([&ctx](const httplib::Request& req, httplib::Response& res) {
    if (IsOpenPath(req.path) ||
        ctx.auth.Allows(req.get_header_value("Authorization"), req.get_header_value("Cookie"))) {
      return httplib::Server::HandlerResponse::Unhandled;
    }
    res.status = 401;
    res.set_header("WWW-Authenticate", "Bearer realm=\"wavebake\"");
    const bool page =
        req.method == "GET" && !absl::StartsWith(req.path, "/api/") && req.path != "/metrics";
    if (page) {  // a browser: offer the login form
      res.set_content(ctx.pages.Get("login.html").value_or("401 unauthorized\n"),
                      "text/html; charset=utf-8");
    } else {
      res.set_content("401 unauthorized: missing or wrong bearer token\n", "text/plain");
    }
    return httplib::Server::HandlerResponse::Handled;
  });
  AddPageRoutes(server, ctx);
  AddJobRoutes(server, ctx);
  AddStoreRoutes(server, ctx);

  const auto& [host, port] = *host_port;
  m->port_ =
      port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, port) ? port : -1);
  if (m->port_ <= 0) {
    return absl::UnavailableError(
        absl::StrCat("listen: cannot listen on \"", options.listen, "\""));
  }
  m->thread_ = std::thread([&server] { server.listen_after_bind(); });
  spdlog::info("web monitor: serving {}", m->url());
  return m;
}

std::string MonitorServer::address() const {
  const std::string& a = options_.listen;
  return absl::StrCat(a.substr(0, a.rfind(':')), ":", port_);
}

std::string MonitorServer::url() const {
  return absl::StrCat(context_ && context_->tls ? "https://" : "http://", address(), "/");
}

void MonitorServer::Stop() {
  if (!server_) return;
  if (context_) context_->stopping = true;
  server_->stop();
  if (thread_.joinable()) thread_.join();
}

MonitorServer::~MonitorServer() { Stop(); }

}  // namespace wavebake::web
