// One whole bake through the product path (driver/bake/embedded_bake.h: the
// coordinator and worker loops in this process), timed phase by phase:
// BAKING (BAKE_TILE × tiles: trace, row transform, transpose, staging
// writes), TRANSFORMING (TRANSFORM_COLUMNS × groups) and FINALIZING, each in
// wall and CPU seconds (the process's user + system time, all threads), with
// the rays traced, the store's size and the peak resident set size.
//
//   build/bench_bake_phases SCENE --out DIR [--layout L] [--light-res N] [--refine on|off]
//                           [--column-mode adaptive|full|2d] [--workers W] [--keep]
//
// The store goes to DIR/bake.wbk and is removed afterwards unless --keep.
// The last line is one JSON object with every number (the big bake of
// docs/RESULTS.md: builtin:cubes-wall --layout camera:512x512 --light-res 128). A plain main():
// linked with Google Benchmark like every bench/*.cc, but a bake is too long to repeat.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/bake_run.h"
#include "core/bake/bake_params_io.h"

namespace wavebake {
namespace {

[[noreturn]] void Die(const std::string& what) {
  std::fprintf(stderr, "bench_bake_phases: %s\n", what.c_str());
  std::exit(1);
}

struct Args {
  std::string scene, layout = "camera", out;
  int light_res = 32, workers = 2;
  bool refine = true, keep = false;
  ColumnMode column_mode = ColumnMode::kAdaptive;
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
    } else if (arg == "--column-mode") {
      absl::StatusOr<ColumnMode> mode = ParseColumnMode(next());
      if (!mode.ok()) Die("--column-mode: " + std::string(mode.status().message()));
      a.column_mode = *mode;
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
          "[--refine on|off] [--column-mode adaptive|full|2d] [--workers W] [--keep]");
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
  params.column_mode = a.column_mode;
  std::filesystem::create_directories(a.out);
  const std::filesystem::path store = std::filesystem::path(a.out) / "bake.wbk";
  absl::StatusOr<bench::PhasedBake> bake = bench::RunPhasedBake(
      a.scene, params, store, a.workers, [](const std::string& phase, double t) {
        std::fprintf(stderr, "%7.1f s  %s\n", t, phase.c_str());
      });
  if (!bake.ok()) Die(bake.status().ToString());
  nlohmann::json out = bake->ToJson();
  out["scene"] = a.scene;
  out["layout"] = a.layout;
  out["light_res"] = a.light_res;
  out["refine"] = a.refine;
  out["column_mode"] = std::string(ToString(a.column_mode));
  out["workers"] = a.workers;
  out["peak_rss_mib"] = bench::PeakRssMiB();
  const bench::PhasedBake& b = *bake;
  std::fprintf(stderr,
               "rays %lld, store %.1f MB, peak RSS %.0f MiB, wall %.1f s (cpu %.1f s): baking "
               "%.1f s (cpu %.1f), transforming %.1f s (cpu %.1f), finalizing %.1f s (cpu %.1f)\n",
               static_cast<long long>(b.rays), b.store_bytes / 1e6, bench::PeakRssMiB(),
               b.total.wall, b.total.cpu, b.baking.wall, b.baking.cpu, b.transforming.wall,
               b.transforming.cpu, b.finalizing.wall, b.finalizing.cpu);
  std::printf("%s\n", out.dump().c_str());
  if (!a.keep) std::filesystem::remove_all(store);
  return 0;
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) { return wavebake::Run(wavebake::Parse(argc, argv)); }
