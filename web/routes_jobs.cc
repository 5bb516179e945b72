// The jobs API: the list (also as a server-sent event stream the jobs page
// follows without reloading), one job, its events (the timeline), cancel.
#include <chrono>
#include <thread>

#include "web/job_json.h"
#include "web/routes.h"

namespace wavebake::web {
namespace {

constexpr int kListedJobs = 50;
constexpr int kTimelineEvents = 20'000;
// A stream ends after this long (the browser's EventSource reconnects), so
// no connection is held forever; updates come at most this often.
constexpr auto kStreamLifetime = std::chrono::minutes(10);
constexpr auto kMinUpdateInterval = std::chrono::milliseconds(250);
constexpr int64_t kChangeWaitMs = 1000;
constexpr auto kKeepAliveInterval = std::chrono::seconds(15);

std::string JobsPayload(const SourceSlot::Use& source) {
  if (!source) return "[]";
  absl::StatusOr<std::vector<v1::Job>> jobs = source->ListJobs(kListedJobs);
  const ClientPaths& paths = source->client_paths();
  if (!jobs.ok())
    return nlohmann::json{{"error", paths(std::string(jobs.status().message()))}}.dump();
  return paths(JobsJson(*jobs).dump());
}

// One client's stream: the jobs list whenever it changed, a comment line as
// keep-alive otherwise.
struct JobStream {
  using Clock = std::chrono::steady_clock;
  Clock::time_point start = Clock::now(), last_polled{}, last_written = Clock::now();
  uint64_t seen = 0;
  std::string last_payload;
  bool first = true;

  // false: end the stream (client gone, server stopping, lifetime over).
  bool Next(const RouteContext& ctx, httplib::DataSink& sink) {
    if (ctx.stopping || Clock::now() - start > kStreamLifetime) {
      sink.done();
      return true;
    }
    if (const auto since = Clock::now() - last_polled; since < kMinUpdateInterval) {
      std::this_thread::sleep_for(kMinUpdateInterval - since);
    }
    std::string payload;
    {
      SourceSlot::Use source = ctx.source->Get();
      if (source && !first) seen = source->WaitForChange(seen, kChangeWaitMs);
      if (!source) std::this_thread::sleep_for(std::chrono::milliseconds(kChangeWaitMs));
      payload = JobsPayload(source);
    }
    first = false;
    last_polled = Clock::now();
    if (payload == last_payload) {
      if (last_polled - last_written < kKeepAliveInterval) return true;
      last_written = last_polled;
      static constexpr char kKeepAlive[] = ": keep-alive\n\n";
      return sink.write(kKeepAlive, sizeof kKeepAlive - 1);
    }
    last_payload = payload;
    last_written = last_polled;
    const std::string event = "event: jobs\ndata: " + payload + "\n\n";
    return sink.write(event.data(), event.size());
  }
};

}  // namespace

void AddJobRoutes(httplib::Server& server, RouteContext& ctx) {
  server.Get("/api/jobs", [&ctx](const httplib::Request&, httplib::Response& res) {
    SourceSlot::Use source = ctx.source->Get();
    res.set_header("Cache-Control", "no-store");
    res.set_content(JobsPayload(source), "application/json");
  });
  server.Get("/api/jobs/stream", [&ctx](const httplib::Request& req, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    StreamSlots::Grant grant = ctx.streams.Take(req.remote_addr);
    if (!grant.slot) {
      res.set_header("Retry-After", "10");
      return SendError(
          res,
          absl::UnavailableError(grant.status == 429 ? "too many event streams from this address"
                                                     : "too many event streams open"),
          grant.status);
    }
    auto stream = std::make_shared<JobStream>();
    res.set_chunked_content_provider(
        "text/event-stream",
        [&ctx, stream, slot = std::move(grant.slot)](size_t, httplib::DataSink& sink) {
          return stream->Next(ctx, sink);
        });
  });
  server.Get(R"(/api/jobs/(\d+))", [&ctx](const httplib::Request& req, httplib::Response& res) {
    SourceSlot::Use source = SourceOr503(ctx, res);
    if (!source) return;
    absl::StatusOr<v1::Job> job = source->GetJob(req.matches[1].str());
    if (!job.ok()) return SendError(res, job.status());
    SendJson(res, JobJson(*job), 200, &source->client_paths());
  });
  server.Post(
      R"(/api/jobs/(\d+)/cancel)", [&ctx](const httplib::Request& req, httplib::Response& res) {
        // Only the pages' own script sends this header (a cross-site
        // form cannot), on top of the SameSite session cookie.
        if (req.get_header_value("X-Wavebake") != "1") {
          return SendError(res, absl::InvalidArgumentError("X-Wavebake: header required (send 1)"));
        }
        SourceSlot::Use source = SourceOr503(ctx, res);
        if (!source) return;
        absl::StatusOr<v1::Job> job = source->CancelJob(req.matches[1].str());
        if (!job.ok()) return SendError(res, job.status());
        SendJson(res, JobJson(*job), 200, &source->client_paths());
      });
  server.Get(R"(/api/jobs/(\d+)/events)",
             [&ctx](const httplib::Request& req, httplib::Response& res) {
               SourceSlot::Use source = SourceOr503(ctx, res);
               if (!source) return;
               absl::StatusOr<std::vector<v1::JobEvent>> events =
                   source->JobEvents(req.matches[1].str(), kTimelineEvents);
               if (!events.ok()) return SendError(res, events.status());
               nlohmann::json out = nlohmann::json::array();
               for (const v1::JobEvent& e : *events) out.push_back(EventJson(e));
               SendJson(res, {{"events", out}, {"truncated", out.size() >= kTimelineEvents}}, 200,
                        &source->client_paths());
             });
}

}  // namespace wavebake::web
