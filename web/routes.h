#pragma once
// The monitor's request handlers, registered on one httplib::Server by
// MonitorServer (web/monitor_server.h): the pages and their files
// (routes_pages.cc), the jobs API with its event stream (routes_jobs.cc), and
// the store, probes and relight API (routes_store.cc), the relight view's
// GPU path (routes_gpu.cc).
#include <httplib.h>

#include <atomic>
#include <nlohmann/json.hpp>
#include <string>

#include "absl/status/status.h"
#include "web/http/stream_slots.h"
#include "web/http/web_auth.h"
#include "web/job_source.h"
#include "web/pages.h"
#include "web/views/job_gpu.h"
#include "web/views/relight_service.h"

namespace wavebake::web {

struct RouteContext {
  RouteContext(SourceSlot* source_slot, std::string token, ProbeCatalogue probes,
               std::filesystem::path pages_dir, bool serves_tls)
      : source(source_slot),
        auth(std::move(token)),
        relight(probes),
        gpu(std::move(probes)),
        pages(std::move(pages_dir)),
        tls(serves_tls) {}
  SourceSlot* source = nullptr;
  WebAuth auth;
  RelightService relight;
  JobGpu gpu;  // the relight view on the browser's GPU
  Pages pages;
  bool tls = false;
  // Half the serving threads at most (web/monitor_server.cc has 16); a
  // browser's tabs past four poll instead.
  StreamSlots streams{8, 4};
  std::atomic<bool> stopping{false};
};

void AddPageRoutes(httplib::Server& server, RouteContext& ctx);
void AddJobRoutes(httplib::Server& server, RouteContext& ctx);
void AddStoreRoutes(httplib::Server& server, RouteContext& ctx);
void AddGpuRoutes(httplib::Server& server, RouteContext& ctx);  // routes_gpu.cc

// JSON bodies; errors as {"error": message} with the status's HTTP code
// (INVALID_ARGUMENT 400, NOT_FOUND 404, FAILED_PRECONDITION 409, ...). The
// server's error handler hides server directories in every error body; a
// body that carries a job's own error passes `paths` itself.
void SendJson(httplib::Response& res, const nlohmann::json& body, int status = 200,
              const ClientPaths* paths = nullptr);
// `http_status` 0: the status code's own (above).
void SendError(httplib::Response& res, const absl::Status& status, int http_status = 0);
// The source, or 503 sent when there is none yet.
SourceSlot::Use SourceOr503(const RouteContext& ctx, httplib::Response& res);

}  // namespace wavebake::web
