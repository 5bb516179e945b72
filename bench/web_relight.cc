// Relight view frame rate (web/views/relight_service.h, web/monitor_server.h): the
// frames a page following the rotation slider gets, beside the bare Eq. 8
// relight of the same store with the same lights (runtime/relight/relighter.h) in the
// same run. `x_relight` is a frame's wall time over the bare relight's; the
// CPU column of Service/* is the frame's CPU time (the service runs on the
// benchmark's thread), beside the bare relight's CPU time printed at start.
//   Service/0: rotate the probe, project, select 256 lights, relight, picture, RGBA
//   Service/1: the same and the frame relit with every wavelet light (the error the page shows)
//   Http/0, 1: Service/0, 1 through GET /api/jobs/1/relight over one keep-alive
//              connection (the page asks /0 while the slider moves, /1 once it rests)
// The store is baked once at start: builtin:cubes-wall, camera 64x64, N = 32
// (WB_BENCH_LAYOUT / WB_BENCH_LIGHT_RES change it), probe grace.hdr.
//   ./build/bench_web_relight --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <httplib.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "driver/bake/embedded_bake.h"
#include "runtime/env/env_map.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"
#include "web/monitor_server.h"
#include "web/views/relight_service.h"

namespace wavebake {
namespace {

double ThreadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

const std::filesystem::path kProbes = std::filesystem::path(WB_SHARED_DATA) / "probes";

struct Fixture {
  std::filesystem::path dir, store;
  double relight_seconds = 0;  // the baseline: one bare Eq. 8 frame

  Fixture() {
    dir = std::filesystem::temp_directory_path() / "wb_bench_web_relight";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    store = dir / "store.wbk";
    BakeParams p;
    p.layout = std::getenv("WB_BENCH_LAYOUT") ? std::getenv("WB_BENCH_LAYOUT") : "camera:64x64";
    p.light_res =
        std::getenv("WB_BENCH_LIGHT_RES") ? std::atoi(std::getenv("WB_BENCH_LIGHT_RES")) : 32;
    absl::StatusOr<v1::Job> job = driver::EmbeddedBake("builtin:cubes-wall", p, store, {});
    if (!job.ok() || job->phase() != v1::PHASE_DONE) std::abort();
    absl::StatusOr<OpenedStore> opened = OpenStore(store);
    absl::StatusOr<EnvMap> env = LoadEnvMap((kProbes / "grace.hdr").string());
    Relighter& r = opened->relighter;
    WaveletLights lights =
        *SelectWaveletLights(*LightingFromEnv(*env, r.light_res(), r.row_filter()), 256);
    std::vector<float> rgb(3 * static_cast<size_t>(r.cells()));
    const int frames = 400;
    std::vector<double> wall, cpu;
    for (int rep = 0; rep < 5; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = ThreadSeconds();
      for (int i = 0; i < frames; ++i) r.Relight(lights, rgb);
      cpu.push_back((ThreadSeconds() - c0) / frames);
      wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() /
                     frames);
    }
    std::sort(wall.begin(), wall.end());
    std::sort(cpu.begin(), cpu.end());
    relight_seconds = wall[2];
    std::fprintf(stderr, "bare relight: %.1f us wall, %.1f us CPU per frame (medians of 5 x %d)\n",
                 wall[2] * 1e6, cpu[2] * 1e6, frames);
  }
  ~Fixture() { std::filesystem::remove_all(dir); }
};

Fixture& Shared() {
  static Fixture f;
  return f;
}

void Report(benchmark::State& state, double seconds) {
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["frame_ms"] = 1e3 * seconds / state.iterations();
  state.counters["x_relight"] = seconds / state.iterations() / Shared().relight_seconds;
}

void BM_BareRelight(benchmark::State& state) {
  // A copy: DoNotOptimize may write its argument back, and the baseline must stay as measured.
  double frame_us = Shared().relight_seconds * 1e6;
  state.counters["frame_us"] = frame_us;
  for (auto _ : state) benchmark::DoNotOptimize(frame_us);
}
BENCHMARK(BM_BareRelight)->Iterations(1);

void BM_Service(benchmark::State& state) {
  Fixture& f = Shared();
  web::RelightService service(*web::ProbeCatalogue::Scan(kProbes));
  web::RelightRequest request{.probe = "grace.hdr", .compare_all = state.range(0) != 0};
  auto no_scene = [] { return absl::StatusOr<Scene>(absl::UnimplementedError("camera layout")); };
  (void)service.Frame(f.store, no_scene, request);  // opens the store and the probe
  double seconds = 0;
  for (auto _ : state) {
    request.rotate_degrees += 1;
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(service.Frame(f.store, no_scene, request));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  Report(state, seconds);
}
BENCHMARK(BM_Service)->Arg(0)->Arg(1)->UseRealTime();

// The web monitor serving the store as job 1.
class OneStore final : public web::JobSource {
 public:
  explicit OneStore(std::filesystem::path store) : store_(std::move(store)) {}
  absl::StatusOr<std::vector<v1::Job>> ListJobs(int) const override {
    return std::vector<v1::Job>{};
  }
  absl::StatusOr<v1::Job> GetJob(const std::string&) const override { return v1::Job{}; }
  absl::StatusOr<v1::Job> CancelJob(const std::string&) override { return v1::Job{}; }
  absl::StatusOr<std::vector<v1::JobEvent>> JobEvents(const std::string&, int) const override {
    return std::vector<v1::JobEvent>{};
  }
  absl::StatusOr<std::filesystem::path> StoreDir(const std::string&) const override {
    return store_;
  }
  absl::StatusOr<Scene> JobScene(const std::string&) const override {
    return absl::UnimplementedError("camera layout");
  }
  SchedulerSnapshot Metrics(int) const override { return {}; }
  uint64_t WaitForChange(uint64_t, int64_t) const override { return 0; }

 private:
  std::filesystem::path store_;
};

void BM_Http(benchmark::State& state) {
  Fixture& f = Shared();
  auto server = *web::MonitorServer::Start(
      {.listen = "127.0.0.1:0", .token = "t", .probes = *web::ProbeCatalogue::Scan(kProbes)},
      std::make_shared<OneStore>(f.store));
  const std::string address = server->address();
  httplib::Client client("127.0.0.1", std::stoi(address.substr(address.rfind(':') + 1)));
  client.set_keep_alive(true);
  client.set_tcp_nodelay(true);
  const httplib::Headers auth = {{"Authorization", "Bearer t"}};
  int degrees = 0;
  double seconds = 0;
  // The server's first frame opens the store and the probe (a second at 256²): not a frame the
  // slider waits for.
  const std::string warm =
      "/api/jobs/1/relight?probe=grace.hdr&compare=" + std::to_string(state.range(0)) + "&rotate=0";
  if (httplib::Result r = client.Get(warm.c_str(), auth); !r || r->status != 200) {
    state.SkipWithError("the first relight request failed");
    return;
  }
  for (auto _ : state) {
    const std::string path =
        "/api/jobs/1/relight?probe=grace.hdr&compare=" + std::to_string(state.range(0)) +
        "&rotate=" + std::to_string(++degrees);
    const auto t0 = std::chrono::steady_clock::now();
    httplib::Result r = client.Get(path.c_str(), auth);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r || r->status != 200) state.SkipWithError("relight request failed");
  }
  Report(state, seconds);
}
BENCHMARK(BM_Http)->Arg(0)->Arg(1)->UseRealTime();

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
