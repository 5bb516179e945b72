// A finished job's store: its statistics (.zattrs), the probes, and relit
// frames for the relight view.
#include <cmath>
#include <cstdio>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "runtime/io/image_io.h"
#include "storage/store/store_reader.h"
#include "web/routes.h"

namespace wavebake::web {
namespace {

// A query parameter as a number; absent: the default; malformed: an error
// naming it.
template <typename T>
absl::StatusOr<T> Param(const httplib::Request& req, const char* name, T fallback) {
  if (!req.has_param(name)) return fallback;
  const std::string text = req.get_param_value(name);
  T v{};
  bool ok = false;
  if constexpr (std::is_same_v<T, int>) {
    ok = absl::SimpleAtoi(text, &v);
  } else {
    ok = absl::SimpleAtod(text, &v) && std::isfinite(v);
  }
  if (!ok)
    return absl::InvalidArgumentError(absl::StrCat(name, ": \"", text, "\" is not a number"));
  return v;
}

absl::StatusOr<RelightRequest> ParseRelight(const httplib::Request& req) {
  RelightRequest r;
  if (req.has_param("probe")) r.probe = req.get_param_value("probe");
  absl::StatusOr<double> rotate = Param(req, "rotate", 0.0);
  if (!rotate.ok()) return rotate.status();
  absl::StatusOr<int> terms = Param(req, "terms", r.terms);
  if (!terms.ok()) return terms.status();
  absl::StatusOr<double> exposure = Param(req, "exposure", 0.0);
  if (!exposure.ok()) return exposure.status();
  r.rotate_degrees = *rotate;
  r.terms = *terms;
  r.exposure_stops = *exposure;
  r.compare_all = req.get_param_value("compare") != "0";
  return r;
}

std::string Fixed(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

void AddStoreRoutes(httplib::Server& server, RouteContext& ctx) {
  server.Get("/api/probes", [&ctx](const httplib::Request&, httplib::Response& res) {
    SendJson(res, {{"probes", ctx.relight.probes().names()}});
  });
  server.Get(R"(/api/jobs/(\d+)/store)",
             [&ctx](const httplib::Request& req, httplib::Response& res) {
               SourceSlot::Use source = SourceOr503(ctx, res);
               if (!source) return;
               absl::StatusOr<std::filesystem::path> dir = source->StoreDir(req.matches[1].str());
               if (!dir.ok()) return SendError(res, dir.status());
               absl::StatusOr<StoreInfo> info = ReadStoreInfo(*dir);
               if (!info.ok()) return SendError(res, info.status());
               const nlohmann::json& a = info->attrs;
               SendJson(res, {{"format", a.value("format", "")},
                              {"layout", a.value("layout", info->params.layout)},
                              {"picture", PictureKindName(PictureKindOf(info->params.layout))},
                              {"width", info->width},
                              {"height", info->height},
                              {"light_res", info->light_res},
                              {"columns", info->columns},
                              {"bits", info->bits},
                              {"params", a.value("params", nlohmann::json::object())},
                              {"stats", a.value("stats", nlohmann::json::object())}});
             });
  server.Get(
      R"(/api/jobs/(\d+)/relight)", [&ctx](const httplib::Request& req, httplib::Response& res) {
        absl::StatusOr<RelightRequest> request = ParseRelight(req);
        if (!request.ok()) return SendError(res, request.status());
        const std::string id = req.matches[1].str();
        absl::StatusOr<RelightFrame> frame;
        {
          SourceSlot::Use source = SourceOr503(ctx, res);
          if (!source) return;
          absl::StatusOr<std::filesystem::path> dir = source->StoreDir(id);
          if (!dir.ok()) return SendError(res, dir.status());
          JobSource* src = source.get();
          frame = ctx.relight.Frame(
              *dir, [src, &id] { return src->JobScene(id); }, *request);
        }
        if (!frame.ok()) return SendError(res, frame.status());
        res.set_header("Cache-Control", "no-store");
        res.set_header("X-Width", absl::StrCat(frame->width));
        res.set_header("X-Height", absl::StrCat(frame->height));
        res.set_header("X-Terms", absl::StrCat(frame->terms));
        res.set_header("X-Columns", absl::StrCat(frame->columns));
        res.set_header("X-Picture", PictureKindName(frame->kind));
        res.set_header("X-Frame-Ms", Fixed(frame->seconds * 1e3));
        if (frame->rel_rms_all >= 0) res.set_header("X-Rel-Rms-All", Fixed(frame->rel_rms_all));
        if (req.get_param_value("format") == "png") {
          absl::StatusOr<std::vector<std::byte>> png =
              EncodePng(frame->width, frame->height, 4, frame->rgba);
          if (!png.ok()) return SendError(res, png.status());
          res.set_content(reinterpret_cast<const char*>(png->data()), png->size(), "image/png");
          return;
        }
        res.set_content(reinterpret_cast<const char*>(frame->rgba.data()), frame->rgba.size(),
                        "application/octet-stream");
      });
}

}  // namespace wavebake::web
