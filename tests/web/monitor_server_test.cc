// The web monitor over real HTTP (cpp-httplib's client) in front of the
// embedded bake, hooked up exactly as `bake --serve` does: the token guards
// every path but /healthz (header or login cookie); the jobs API and
// /metrics agree with the job; the relight view's frames obey the white
// furnace (camera and mesh pictures) and change with the rotation; a client
// never names a server file.
#include "web/monitor_server.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "driver/bake/embedded_bake.h"
#include "runtime/io/tonemap.h"
#include "storage/store/store_reader.h"
#include "tests/testing/scratch_dir.h"
#include "web/coordinator_source.h"

namespace wavebake::web {
namespace {

using test_support::ScratchDir;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr char kToken[] = "s3cret-token";

// A furnace bake served by a monitor: the bake runs once per layout.
class MonitorServerTest : public ::testing::Test {
 protected:
  void Bake(const std::string& layout, const std::string& scene = "builtin:furnace") {
    absl::StatusOr<std::unique_ptr<MonitorServer>> server =
        MonitorServer::Start({.listen = "127.0.0.1:0", .token = kToken}, nullptr);
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
    BakeParams p;
    p.light_res = 8;
    p.layout = layout;
    p.tile_size = 8;
    p.column_group = 128;
    std::shared_ptr<JobSource> live;
    driver::EmbeddedBakeOptions options{.workers = 2};
    options.on_started = [&](Coordinator& c, const PlannerOptions& planner) {
      live = CoordinatorSource(c, planner);
      server_->SetSource(live);
    };
    options.on_ending = [&](Coordinator&, const std::string& id) {
      // While the coordinator still runs, the live source answers.
      live_metrics_ = Get("/metrics", true);
      server_->SetSource(*FrozenJob(*live, id, dir_.path() / "out.wbk"));
      live.reset();
    };
    absl::StatusOr<v1::Job> job = driver::EmbeddedBake(scene, p, dir_.path() / "out.wbk", options);
    ASSERT_TRUE(job.ok()) << job.status();
    ASSERT_EQ(job->phase(), v1::PHASE_DONE);
    job_ = *job;
  }

  httplib::Client Client() const {
    httplib::Client c("127.0.0.1",
                      std::stoi(server_->address().substr(server_->address().rfind(':') + 1)));
    c.set_read_timeout(30);
    return c;
  }
  std::string Get(const std::string& path, bool token, int want = 200) {
    httplib::Client c = Client();
    httplib::Headers h;
    if (token) h.emplace("Authorization", std::string("Bearer ") + kToken);
    httplib::Result r = c.Get(path.c_str(), h);
    EXPECT_TRUE(r) << path;
    if (!r) return "";
    EXPECT_EQ(r->status, want) << path << ": " << r->body;
    return r->body;
  }
  // A relit frame's RGBA bytes and headers.
  httplib::Result Frame(const std::string& query) {
    httplib::Client c = Client();
    return c.Get(("/api/jobs/" + job_.id() + "/relight?" + query).c_str(),
                 {{"Authorization", std::string("Bearer ") + kToken}});
  }

  ScratchDir dir_{"monitor"};
  std::unique_ptr<MonitorServer> server_;
  v1::Job job_;
  std::string live_metrics_;
};

// sRGB 8-bit back to linear (IEC 61966-2-1), independent of runtime/tonemap.
double Linear(uint8_t v) {
  const double c = v / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Every covered pixel of a furnace frame under L ≡ 1 shows B = albedo = 1
// (DESIGN.md §1, the white-furnace test); at −1 stop that is linear 0.5, so
// no clamping hides an error. Within the bake's 1 % target (RMS) and 8 bits.
void ExpectFurnace(const std::string& rgba, int min_covered) {
  const std::array<uint8_t, 3> background =
      ToneMapPixel({NAN, NAN, NAN}, 1, {0.02f, 0.02f, 0.025f});
  int covered = 0;
  double sum2 = 0, worst = 0;
  for (size_t p = 0; p + 3 < rgba.size(); p += 4) {
    const uint8_t px[3] = {static_cast<uint8_t>(rgba[p]), static_cast<uint8_t>(rgba[p + 1]),
                           static_cast<uint8_t>(rgba[p + 2])};
    if (px[0] == background[0] && px[1] == background[1] && px[2] == background[2]) continue;
    ++covered;
    for (uint8_t v : px) {
      const double e = 2 * Linear(v) - 1;
      sum2 += e * e;
      worst = std::max(worst, std::abs(e));
    }
  }
  ASSERT_GE(covered, min_covered);
  EXPECT_LT(std::sqrt(sum2 / (3.0 * covered)), 0.015) << "rms |B - 1| over " << covered;
  EXPECT_LT(worst, 0.08);
}

TEST_F(MonitorServerTest, TokenGuardsEverythingButHealthz) {
  Bake("camera:16x16");
  EXPECT_EQ(Get("/healthz", false), "ok\n");
  EXPECT_THAT(Get("/", false, 401), HasSubstr("name=\"token\""));  // the login form
  Get("/metrics", false, 401);
  Get("/api/jobs", false, 401);
  Get("/api/jobs/" + job_.id() + "/relight", false, 401);
  httplib::Client c = Client();
  httplib::Result wrong = c.Get("/api/jobs", {{"Authorization", "Bearer nope"}});
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 401);
  EXPECT_THAT(Get("/", true), HasSubstr("monitor.js"));

  // A browser signs in with the token in a form and gets a session cookie.
  httplib::Result bad = c.Post("/login", "token=nope", "application/x-www-form-urlencoded");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 401);
  httplib::Result good =
      c.Post("/login", std::string("token=") + kToken, "application/x-www-form-urlencoded");
  ASSERT_TRUE(good);
  EXPECT_EQ(good->status, 303);
  const std::string cookie = good->get_header_value("Set-Cookie");
  EXPECT_THAT(cookie, HasSubstr("HttpOnly"));
  EXPECT_THAT(cookie, HasSubstr("SameSite=Strict"));
  httplib::Result page = c.Get("/api/jobs", {{"Cookie", cookie.substr(0, cookie.find(';'))}});
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  httplib::Result forged = c.Get("/api/jobs", {{"Cookie", "wavebake_session=0123"}});
  ASSERT_TRUE(forged);
  EXPECT_EQ(forged->status, 401);
}

TEST_F(MonitorServerTest, JobsAndMetricsAgreeWithTheJob) {
  Bake("camera:16x16");
  const nlohmann::json jobs = nlohmann::json::parse(Get("/api/jobs", true));
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0]["phase"], "DONE");
  EXPECT_EQ(jobs[0]["tasks_done"], job_.tasks_total());
  EXPECT_EQ(jobs[0]["eta_seconds"], 0);
  // The live coordinator's counters: every task leased and completed once.
  // The job is DONE: it has no per-job series any more (live jobs only).
  EXPECT_THAT(live_metrics_, Not(HasSubstr("job_id=\"" + job_.id() + "\"")));
  EXPECT_THAT(live_metrics_,
              HasSubstr("wavebake_tasks_completed_total{kind=\"finalize\"} " +
                        std::to_string(job_.tasks_total() - job_.tiles() - job_.groups())));
  EXPECT_THAT(live_metrics_, HasSubstr("wavebake_tasks_completed_total{kind=\"bake_tile\"} " +
                                       std::to_string(job_.tiles())));
  EXPECT_THAT(live_metrics_,
              HasSubstr("wavebake_tasks_completed_total{kind=\"transform_columns\"} " +
                        std::to_string(job_.groups())));
  EXPECT_THAT(live_metrics_, HasSubstr("wavebake_jobs{phase=\"done\"} 1"));
  EXPECT_THAT(live_metrics_,
              HasSubstr("wavebake_rays_traced_total " + std::to_string(job_.rays_traced())));
  const nlohmann::json events =
      nlohmann::json::parse(Get("/api/jobs/" + job_.id() + "/events", true));
  int leased = 0, done = 0;
  for (const nlohmann::json& e : events["events"]) {
    leased += e["kind"] == "TASK_LEASED";
    done += e["kind"] == "TASK_DONE";
  }
  EXPECT_EQ(done, job_.tasks_total());
  EXPECT_GE(leased, done);
  const nlohmann::json store =
      nlohmann::json::parse(Get("/api/jobs/" + job_.id() + "/store", true));
  EXPECT_EQ(store["picture"], "camera image");
  EXPECT_EQ(store["columns"], 6 * 8 * 8);
  EXPECT_GT(store["stats"]["nnz"].get<int64_t>(), 0);
  Get("/api/jobs/999/store", true, 404);
  Get("/api/jobs/" + job_.id() + "/cancel", true, 404);  // GET: no such route
}

// Differing channel values of two frames.
int Differing(const std::string& a, const std::string& b) {
  int n = 0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) n += std::abs(a[i] - b[i]) > 1;
  return n;
}

TEST_F(MonitorServerTest, CameraFramesObeyTheFurnace) {
  Bake("camera:16x16");
  httplib::Result r = Frame("probe=builtin:constant&exposure=-1&terms=100000");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("X-Width"), "16");
  EXPECT_EQ(r->body.size(), 16u * 16 * 4);
  ExpectFurnace(r->body, 100);
  // An unoccluded plane's irradiance does not change when the sky turns
  // about the plane's normal (+Y).
  httplib::Result a = Frame("probe=builtin:sky&rotate=0&terms=100000");
  httplib::Result b = Frame("probe=builtin:sky&rotate=120&terms=100000");
  ASSERT_TRUE(a && b);
  EXPECT_EQ(Differing(a->body, b->body), 0);
}

TEST_F(MonitorServerTest, OccludedFramesFollowTheRotation) {
  Bake("camera:16x16", "builtin:cubes-wall");
  httplib::Result a = Frame("probe=builtin:sky&rotate=0&terms=64");
  httplib::Result b = Frame("probe=builtin:sky&rotate=120&terms=64");
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->status, 200);
  ASSERT_EQ(b->status, 200);
  EXPECT_GT(Differing(a->body, b->body), 100);  // the cubes' shadows turn with the sun
  const double error = std::stod(a->get_header_value("X-Rel-Rms-All"));
  EXPECT_GT(error, 0);  // 64 of 384 lights under a sun: not exact
  EXPECT_LT(error, 1);
  httplib::Result all = Frame("probe=builtin:sky&terms=384");
  ASSERT_TRUE(all);
  // Every nonzero light: the same sum as all of them, to float rounding.
  EXPECT_LT(std::stod(all->get_header_value("X-Rel-Rms-All")), 1e-6);
  EXPECT_LE(std::stoi(all->get_header_value("X-Terms")), 384);
  httplib::Result png = Frame("probe=builtin:sky&format=png");
  ASSERT_TRUE(png);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(png->body.substr(1, 3), "PNG");
}

TEST_F(MonitorServerTest, MeshStoresShowVertexColoursOnTheMesh) {
  Bake("grid");
  httplib::Result r = Frame("probe=builtin:constant&exposure=-1&terms=100000");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("X-Picture"), "vertex colours");
  EXPECT_EQ(r->get_header_value("X-Width"), "256");  // the picture, not the grid
  ExpectFurnace(r->body, 2000);
}

TEST_F(MonitorServerTest, UvStoresShowTheirLightmapWithGutters) {
  Bake("uv:64x64", std::string(WB_SHARED_DATA) + "/models/spot.obj");
  httplib::Result r = Frame("probe=builtin:constant&terms=100000");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("X-Picture"), "lightmap");
  EXPECT_EQ(r->get_header_value("X-Width"), "64");
  // Every texel with a sample is shown, and gutter texels around the charts too.
  absl::StatusOr<SampleSet> samples = ReadSamples(dir_.path() / "out.wbk");
  ASSERT_TRUE(samples.ok()) << samples.status();
  const std::array<uint8_t, 3> background =
      ToneMapPixel({NAN, NAN, NAN}, 1, {0.02f, 0.02f, 0.025f});
  int shown = 0, hidden_samples = 0, sampled = 0;
  for (size_t cell = 0; cell < samples->grid.size(); ++cell) {
    const char* px = &r->body[4 * cell];
    const bool is_background = static_cast<uint8_t>(px[0]) == background[0] &&
                               static_cast<uint8_t>(px[1]) == background[1] &&
                               static_cast<uint8_t>(px[2]) == background[2];
    shown += !is_background;
    if (samples->grid[cell] >= 0) {
      ++sampled;
      hidden_samples += is_background;
    }
  }
  EXPECT_GT(sampled, 500);
  EXPECT_EQ(hidden_samples, 0);
  EXPECT_GT(shown, sampled);  // the gutters
  EXPECT_THAT(Get("/api/jobs/" + job_.id() + "/store", true),
              HasSubstr("\"picture\":\"lightmap\""));
}

TEST_F(MonitorServerTest, ClientsNameProbesNeverFiles) {
  Bake("camera:16x16");
  httplib::Result r = Frame("probe=/etc/passwd");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_THAT(r->body, HasSubstr("not one of the server's probes"));
  r = Frame("probe=builtin:sky&terms=zero");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_THAT(r->body, HasSubstr("terms"));
  Get("/static/..%2fCMakeCache.txt", true, 404);
  Get("/static/nothing.js", true, 404);
  EXPECT_THAT(Get("/api/probes", true), HasSubstr("builtin:sky"));
}

// An error of the store reaches the client with the store root as a label,
// as the JobService hides it: no directory of the server in any body.
TEST_F(MonitorServerTest, StoreErrorsNameNoServerDirectory) {
  Bake("camera:16x16");
  const std::filesystem::path data = dir_.path() / "out.wbk" / "transport" / "data";
  ASSERT_TRUE(std::filesystem::is_directory(data));
  for (const auto& chunk : std::filesystem::directory_iterator(data))
    std::filesystem::remove_all(chunk.path());
  httplib::Result r = Frame("probe=builtin:sky");
  ASSERT_TRUE(r);
  EXPECT_GE(r->status, 400);
  EXPECT_THAT(r->body, HasSubstr("<store root>"));
  EXPECT_EQ(r->body.find(dir_.path().string()), std::string::npos) << r->body;
  const nlohmann::json error = nlohmann::json::parse(r->body);  // still whole JSON
  EXPECT_TRUE(error.contains("error"));
}

// --http-pages: the built-in file names, read from the directory; no other
// file of it is served.
TEST(MonitorPagesTest, APagesDirectoryServesOnlyTheBuiltInNames) {
  ScratchDir dir("pages");
  std::ofstream(dir.path() / "index.html") << "<p>edited</p>";
  std::ofstream(dir.path() / "secret.txt") << "no";
  absl::StatusOr<std::unique_ptr<MonitorServer>> server =
      MonitorServer::Start({.listen = "127.0.0.1:0", .pages_dir = dir.path()}, nullptr);
  ASSERT_TRUE(server.ok()) << server.status();
  const std::string a = (*server)->address();
  httplib::Client c("127.0.0.1", std::stoi(a.substr(a.rfind(':') + 1)));
  httplib::Result index = c.Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->body, "<p>edited</p>");
  httplib::Result secret = c.Get("/static/secret.txt");
  ASSERT_TRUE(secret);
  EXPECT_EQ(secret->status, 404);
  httplib::Result jobs = c.Get("/api/jobs");  // no token configured, no source yet
  ASSERT_TRUE(jobs);
  EXPECT_EQ(jobs->body, "[]");
  EXPECT_FALSE(MonitorServer::Start({.listen = "127.0.0.1"}, nullptr).ok());  // no port
}

}  // namespace
}  // namespace wavebake::web
