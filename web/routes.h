#pragma once
// The monitor's request handlers, registered on one httplib::Server by
// MonitorServer (web/monitor_server.h): the pages and their files
// (routes_pages.cc), the jobs API with its event stream (routes_jobs.cc), and
// the store, probes and relight API (routes_store.cc).
#include <httplib.h>

#include <atomic>
#include <nlohmann/json.hpp>
#include <string>

#include "absl/status/status.h"
#include "web/job_source.h"
#include "web/pages.h"
#include "web/relight_service.h"
#include "web/web_auth.h"

namespace wavebake::web {

struct RouteContext {
  RouteContext(SourceSlot* source_slot, std::string token, ProbeCatalogue probes,
               std::filesystem::path pages_dir, bool serves_tls)
      : source(source_slot),
        auth(std::move(token)),
        relight(std::move(probes)),
        pages(std::move(pages_dir)),
        tls(serves_tls) {}
  SourceSlot* source = nullptr;
  WebAuth auth;
  RelightService relight;
  Pages pages;
  bool tls = false;
  std::atomic<bool> stopping{false};
};

void AddPageRoutes(httplib::Server& server, RouteContext& ctx);
void AddJobRoutes(httplib::Server& server, RouteContext& ctx);
void AddStoreRoutes(httplib::Server& server, RouteContext& ctx);

// JSON bodies; errors as {"error": message} with the status's HTTP code
// (INVALID_ARGUMENT 400, NOT_FOUND 404, FAILED_PRECONDITION 409, ...).
void SendJson(httplib::Response& res, const nlohmann::json& body, int status = 200);
void SendError(httplib::Response& res, const absl::Status& status);
// The source, or 503 sent when there is none yet.
SourceSlot::Use SourceOr503(const RouteContext& ctx, httplib::Response& res);

}  // namespace wavebake::web
