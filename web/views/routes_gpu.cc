// The job page's GPU relight path (web/views/job_gpu.h): a finished job's store
// arrays and, per frame, its kept lights.
#include "absl/strings/numbers.h"
#include "web/routes.h"
#include "web/views/job_gpu.h"

namespace wavebake::web {
namespace {

std::shared_ptr<const ServedColumns> ColumnsOfJob(RouteContext& ctx, const httplib::Request& req,
                                                  httplib::Response& res) {
  SourceSlot::Use source = SourceOr503(ctx, res);
  if (!source) return nullptr;
  absl::StatusOr<std::filesystem::path> dir = source->StoreDir(req.matches[1].str());
  if (!dir.ok()) {
    SendError(res, dir.status());
    return nullptr;
  }
  absl::StatusOr<std::shared_ptr<const ServedColumns>> c = ctx.gpu.Open(*dir);
  if (!c.ok()) {
    SendError(res, c.status());
    return nullptr;
  }
  return *c;
}

}  // namespace

void AddGpuRoutes(httplib::Server& server, RouteContext& ctx) {
  AddColumnArrayRoutes(server, R"(/api/jobs/(\d+)/gpu/)",
                       [&ctx](const httplib::Request& req, httplib::Response& res) {
                         return ColumnsOfJob(ctx, req, res);
                       });
  server.Get(
      R"(/api/jobs/(\d+)/gpu/lights)", [&ctx](const httplib::Request& req, httplib::Response& res) {
        std::shared_ptr<const ServedColumns> c = ColumnsOfJob(ctx, req, res);
        if (!c) return;
        std::string probe = "builtin:sky";
        double rotate = 0;
        int terms = 256;
        if (req.has_param("probe")) probe = req.get_param_value("probe");
        if (req.has_param("rotate") && !absl::SimpleAtod(req.get_param_value("rotate"), &rotate))
          return SendError(res, absl::InvalidArgumentError("rotate: not a number"));
        if (req.has_param("terms") && !absl::SimpleAtoi(req.get_param_value("terms"), &terms))
          return SendError(res, absl::InvalidArgumentError("terms: not an integer"));
        absl::StatusOr<WaveletLights> lights =
            ctx.gpu.lights().Lights(probe, rotate, terms, c->light_res, c->support);
        if (!lights.ok()) return SendError(res, lights.status());
        SendBytes(res, LightsBody(*lights));
      });
}

}  // namespace wavebake::web
