// What every handler of web/routes.h shares: JSON replies and error codes.
#include "web/routes.h"

namespace wavebake::web {
namespace {

int HttpStatus(const absl::Status& s) {
  switch (s.code()) {
    case absl::StatusCode::kInvalidArgument:
    case absl::StatusCode::kOutOfRange:
      return 400;
    case absl::StatusCode::kUnauthenticated:
      return 401;
    case absl::StatusCode::kPermissionDenied:
      return 403;
    case absl::StatusCode::kNotFound:
      return 404;
    case absl::StatusCode::kFailedPrecondition:
    case absl::StatusCode::kAlreadyExists:
      return 409;
    case absl::StatusCode::kUnavailable:
      return 503;
    default:
      return 500;
  }
}

}  // namespace

void SendJson(httplib::Response& res, const nlohmann::json& body, int status,
              const ClientPaths* paths) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  // Replace, never throw, on invalid UTF-8 from a message or a file name.
  std::string text = body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (paths != nullptr) text = (*paths)(std::move(text));
  res.set_content(text, "application/json");
}

void SendError(httplib::Response& res, const absl::Status& status, int http_status) {
  SendJson(
      res,
      {{"error", std::string(status.message())}, {"code", absl::StatusCodeToString(status.code())}},
      http_status != 0 ? http_status : HttpStatus(status));
}

SourceSlot::Use SourceOr503(const RouteContext& ctx, httplib::Response& res) {
  SourceSlot::Use use = ctx.source->Get();
  if (!use) SendError(res, absl::UnavailableError("no coordinator is running yet"));
  return use;
}

}  // namespace wavebake::web
