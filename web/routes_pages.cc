// The pages and their files, the login form, /healthz and /metrics.
#include "absl/strings/str_cat.h"
#include "web/metrics_text.h"
#include "web/routes.h"

namespace wavebake::web {
namespace {

// Per-job series in /metrics are for live jobs only (finished ones are summed
// by phase); this caps them too, so a deep queue cannot grow a scrape unbounded.
constexpr int kMetricsJobs = 100;

void SendPage(const RouteContext& ctx, const std::string& name, httplib::Response& res) {
  std::optional<std::string> body = ctx.pages.Get(name);
  if (!body) {
    res.status = 404;
    res.set_content("not found\n", "text/plain");
    return;
  }
  res.set_header("Cache-Control", "no-cache");
  // The pages load only their own files and talk only to this server.
  res.set_header("Content-Security-Policy",
                 "default-src 'self'; img-src 'self' data: blob:; style-src 'self'");
  res.set_content(*body, Pages::ContentType(name));
}

}  // namespace

void AddPageRoutes(httplib::Server& server, RouteContext& ctx) {
  server.Get("/", [&ctx](const httplib::Request&, httplib::Response& res) {
    SendPage(ctx, "index.html", res);
  });
  server.Get(R"(/jobs/(\d+))", [&ctx](const httplib::Request&, httplib::Response& res) {
    SendPage(ctx, "job.html", res);
  });
  server.Get(R"(/static/([A-Za-z0-9_.-]+))",
             [&ctx](const httplib::Request& req, httplib::Response& res) {
               SendPage(ctx, req.matches[1].str(), res);
             });
  server.Get("/login", [&ctx](const httplib::Request&, httplib::Response& res) {
    SendPage(ctx, "login.html", res);
  });
  server.Post("/login", [&ctx](const httplib::Request& req, httplib::Response& res) {
    std::optional<std::string> session = ctx.auth.Login(req.get_param_value("token"));
    if (!session) {
      res.status = 401;
      SendPage(ctx, "login.html", res);
      res.status = 401;
      return;
    }
    res.set_header("Set-Cookie", WebAuth::SessionCookie(*session, ctx.tls));
    res.set_redirect("/", 303);
  });
  server.Get("/healthz", [](const httplib::Request&, httplib::Response& res) {
    res.set_content("ok\n", "text/plain");
  });
  server.Get("/metrics", [&ctx](const httplib::Request&, httplib::Response& res) {
    SourceSlot::Use source = ctx.source->Get();
    absl::StatusOr<ProcessStats> process = ReadProcessStats();
    res.set_content(MetricsText(source ? source->Metrics(kMetricsJobs) : SchedulerSnapshot{},
                                process.ok() ? &*process : nullptr),
                    kMetricsContentType);
  });
}

}  // namespace wavebake::web
