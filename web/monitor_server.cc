#include "web/monitor_server.h"

#include <openssl/ssl.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <system_error>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "web/http/http_gate.h"
#include "web/http/socket_stream.h"
#include "web/routes.h"

namespace wavebake::web {
namespace {

// Event streams hold a thread each (at most half of them, routes_jobs.cc);
// relight frames want a few.
constexpr int kServerThreads = 16;
constexpr auto kWriteTimeout = std::chrono::seconds(5);

// cpp-httplib's routing without its accept loop and thread pool: the gate
// hands over connections whose request has arrived, one request each.
class GatedServer final : public httplib::Server {
 public:
  void ServeOne(httplib::Stream& stream) {
    bool closed = false;
    process_request(stream, /*close_connection=*/true, closed, nullptr);
  }
  ~GatedServer() override { Shut(); }
  // A socket of its own for the gate: cpp-httplib ends a chunked response
  // (an event stream) as soon as its listening socket is gone.
  int ListenSocket() const { return ::dup(svr_sock_); }
  // Streams end at their next chunk.
  void Shut() {
    const int fd = svr_sock_.exchange(INVALID_SOCKET);
    if (fd != INVALID_SOCKET) ::close(fd);
  }
};

// The certificate chain and key as cpp-httplib's SSLServer loads them.
SSL_CTX* NewSslContext(const std::filesystem::path& cert, const std::filesystem::path& key) {
  SSL_CTX* ctx = SSL_CTX_new(TLS_server_method());
  if (ctx == nullptr) return nullptr;
  SSL_CTX_set_options(ctx, SSL_OP_NO_COMPRESSION | SSL_OP_NO_SESSION_RESUMPTION_ON_RENEGOTIATION);
  SSL_CTX_set_min_proto_version(ctx, TLS1_2_VERSION);
  if (SSL_CTX_use_certificate_chain_file(ctx, cert.c_str()) != 1 ||
      SSL_CTX_use_PrivateKey_file(ctx, key.c_str(), SSL_FILETYPE_PEM) != 1 ||
      SSL_CTX_check_private_key(ctx) != 1) {
    SSL_CTX_free(ctx);
    return nullptr;
  }
  return ctx;
}

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
    m->ssl_ctx_ = {NewSslContext(options.tls_cert, options.tls_key), SSL_CTX_free};
    if (!m->ssl_ctx_)
      return absl::InvalidArgumentError(
          absl::StrCat("tls_cert/tls_key: ", options.tls_cert.string(), " and ",
                       options.tls_key.string(), " are not a PEM certificate and its key"));
  }
  auto gated = std::make_unique<GatedServer>();
  GatedServer& server = *gated;
  m->server_ = std::move(gated);
  m->options_ = options;
  m->source_.Set(std::move(source));
  m->context_ = std::make_unique<RouteContext>(&m->source_, options.token, options.probes,
                                               options.pages_dir, tls);

  server.set_payload_max_length(HeadLimits{}.max_body);  // the gate refuses more anyway
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
  // No error leaves with a server directory in it (DESIGN.md §4): the
  // store's messages name its files. Here, before cpp-httplib sizes and
  // compresses the body; the jobs' own errors are redacted by their routes.
  server.set_error_handler(
      httplib::Server::HandlerWithResponse([&ctx](const httplib::Request&, httplib::Response& res) {
        if (!res.body.empty())
          if (SourceSlot::Use source = ctx.source->Get())
            res.body = source->client_paths()(std::move(res.body));
        return httplib::Server::HandlerResponse::Unhandled;
      }));
  AddPageRoutes(server, ctx);
  AddJobRoutes(server, ctx);
  AddStoreRoutes(server, ctx);
  AddGpuRoutes(server, ctx);

  const auto& [host, port] = *host_port;
  m->port_ =
      port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, port) ? port : -1);
  if (m->port_ <= 0) {
    return absl::UnavailableError(
        absl::StrCat("listen: cannot listen on \"", options.listen, "\""));
  }
  SSL_CTX* ssl = m->ssl_ctx_.get();
  m->gate_ = std::make_unique<HttpGate>(server.ListenSocket(),
                                        GateOptions{.threads = kServerThreads, .tls = tls},
                                        [&server, ssl](int fd, StreamClock::time_point deadline) {
                                          {
                                            SocketStream stream(fd, ssl, deadline, kWriteTimeout);
                                            if (stream.Handshake()) server.ServeOne(stream);
                                          }
                                          ::shutdown(fd, SHUT_RDWR);
                                          ::close(fd);
                                        });
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
  if (context_) context_->stopping = true;
  if (server_) static_cast<GatedServer&>(*server_).Shut();
  if (gate_) gate_->Stop();
}

MonitorServer::~MonitorServer() { Stop(); }

}  // namespace wavebake::web
