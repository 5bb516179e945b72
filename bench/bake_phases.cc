// One whole bake through the product path (driver/embedded_bake.h: the
// coordinator and worker loops in this process), timed phase by phase:
// BAKING (BAKE_TILE × tiles: trace, row transform, transpose, staging
// writes), TRANSFORMING (TRANSFORM_COLUMNS × groups) and FINALIZING, each in
// wall and CPU seconds (the process's user + system time, all threads), with
// the rays traced, the store's size and the peak resident set size.
//
//   build/bench_bake_phases SCENE --out DIR [--layout L] [--light-res N] [--refine on|off]
//                           [--workers W] [--keep]
//
// The store goes to DIR/bake.wbk and is removed afterwards unless --keep.
// The last line is one JSON object with every number (bench/bake_speed.sh
// and the big bake of docs/RESULTS.md read it). A plain main(): linked with
// Google Benchmark like every bench/*.cc, but a bake is too long to repeat.
#include <sys/resource.h>
#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "driver/embedded_bake.h"
#include "driver/job_query.h"
#include "worker/store_manifest.h"

namespace wavebake {
namespace {

[[noreturn]] void Die(const std::string& what) {
  std::fprintf(stderr, "bench_bake_phases: %s\n", what.c_str());
  std::exit(1);
}

double CpuSeconds() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec +
         1e-6 * u.ru_stime.tv_usec;
}

double PeakRssMiB() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // Linux: kilobytes
}

struct Mark {
  double wall = 0, cpu = 0;
};

struct Args {
  std::string scene, layout = "camera", out;
  int light_res = 32, workers = 2;
  bool refine = true, keep = false;
};

Args Parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) Die(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--layout") {
      a.layout = next();
    } else if (arg == "--light-res") {
      a.light_res = std::atoi(next().c_str());
    } else if (arg == "--refine") {
      const std::string v = next();
      if (v != "on" && v != "off") Die("--refine: on or off");
      a.refine = v == "on";
    } else if (arg == "--workers") {
      a.workers = std::atoi(next().c_str());
    } else if (arg == "--out") {
      a.out = next();
    } else if (arg == "--keep") {
      a.keep = true;
    } else if (a.scene.empty() && !arg.empty() && arg[0] != '-') {
      a.scene = arg;
    } else {
      Die("usage: bench_bake_phases SCENE --out DIR [--layout L] [--light-res N] "
          "[--refine on|off] [--workers W] [--keep]");
    }
  }
  if (a.scene.empty() || a.out.empty()) Die("SCENE and --out DIR are required");
  return a;
}

int Run(const Args& a) {
  BakeParams params;
  params.layout = a.layout;
  params.light_res = a.light_res;
  params.refine = a.refine;
  std::filesystem::create_directories(a.out);
  const std::filesystem::path store = std::filesystem::path(a.out) / "bake.wbk";

  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const double cpu0 = CpuSeconds();
  auto now = [&] {
    return Mark{std::chrono::duration<double>(Clock::now() - t0).count(), CpuSeconds() - cpu0};
  };
  std::map<v1::Phase, Mark> started;  // first event of each phase
  v1::Phase last = v1::PHASE_UNSPECIFIED;
  auto on_event = [&](const v1::JobEvent& e) {
    if (e.phase() == last) return;
    last = e.phase();
    started.emplace(e.phase(), now());
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    std::fprintf(stderr, "%7.1f s  %s (monotonic %.3f)\n", now().wall,
                 v1::Phase_Name(e.phase()).c_str(), ts.tv_sec + 1e-9 * ts.tv_nsec);
  };
  absl::StatusOr<v1::Job> job =
      driver::EmbeddedBake(a.scene, params, store, {.workers = a.workers, .on_event = on_event});
  if (!job.ok()) Die(job.status().ToString());
  if (job->phase() != v1::PHASE_DONE) Die(driver::JobOutcome(*job));
  const Mark end = now();

  auto span = [&](v1::Phase from, v1::Phase to) {
    const Mark a_ = started.count(from) ? started[from] : Mark{};
    const Mark b_ = started.count(to) ? started[to] : end;
    return nlohmann::json{{"wall_s", b_.wall - a_.wall}, {"cpu_s", b_.cpu - a_.cpu}};
  };
  nlohmann::json out = {
      {"scene", a.scene},
      {"layout", a.layout},
      {"light_res", a.light_res},
      {"refine", a.refine},
      {"workers", a.workers},
      {"rays", job->rays_traced()},
      {"tiles", job->tiles()},
      {"groups", job->groups()},
      {"store_bytes", DirectoryBytes(store)},
      {"peak_rss_mib", PeakRssMiB()},
      {"wall_s", end.wall},
      {"cpu_s", end.cpu},
      {"setup", span(v1::PHASE_UNSPECIFIED, v1::PHASE_BAKING)},
      {"baking", span(v1::PHASE_BAKING, v1::PHASE_TRANSFORMING)},
      {"transforming", span(v1::PHASE_TRANSFORMING, v1::PHASE_FINALIZING)},
      {"finalizing", span(v1::PHASE_FINALIZING, v1::PHASE_DONE)},
  };
  std::fprintf(stderr,
               "rays %lld, store %.1f MB, peak RSS %.0f MiB, wall %.1f s (cpu %.1f s): baking "
               "%.1f s (cpu %.1f), transforming %.1f s (cpu %.1f), finalizing %.1f s (cpu %.1f)\n",
               static_cast<long long>(job->rays_traced()), out["store_bytes"].get<double>() / 1e6,
               out["peak_rss_mib"].get<double>(), end.wall, end.cpu,
               out["baking"]["wall_s"].get<double>(), out["baking"]["cpu_s"].get<double>(),
               out["transforming"]["wall_s"].get<double>(),
               out["transforming"]["cpu_s"].get<double>(),
               out["finalizing"]["wall_s"].get<double>(), out["finalizing"]["cpu_s"].get<double>());
  std::printf("%s\n", out.dump().c_str());
  if (!a.keep) std::filesystem::remove_all(store);
  return 0;
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) { return wavebake::Run(wavebake::Parse(argc, argv)); }
