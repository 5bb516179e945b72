// Visibility refinement against brute force, whole bakes, in one run: the
// ratios the speed goals ask for, printed side by side.
//
//   build/bench_refine_bake WORK_DIR [--quick] [--workers W] [--bake-res N] [--repeat R]
//                           [--fixed-depth]
//
// Cases: builtin:cubes-wall on camera:256x256, spot.obj and the bunny on
// hilbert:64x64 (../shared/data). For each, at N = 64:
//   * two bakes through the product path (driver/bake/embedded_bake.h, W workers,
//     default 2): --refine off and on; rays, wall and CPU seconds, store size;
//   * each store's relighting error against the independent reference under
//     grace.hdr and pisa.hdr with the runtime's default 256 wavelet lights —
//     `eval --reference --no-dense`'s compressed rel_rms: the same reference
//     (same samples, seed and ray offset) traced once and used for both
//     stores (driver/eval/reference_measure.h);
// and at N = 128 the rays alone: refinement's, traced row by row, against the
// rays brute force would trace (core/transport/transport_row.h BruteForceRays, counted
// without tracing).
//
// Targets: refined rays ≤ 0.25× brute force (≤ 0.12× at N = 128), whole-bake
// wall and CPU time ≤ 0.35× (≤ 0.25× with --bake-res 128: whole bakes at
// N = 128), the refined bake's column stage and
// FINALIZE ≤ 0.15× of the brute-force bake's CPU (spot and the bunny; printed
// as x_cols), error within +0.002 of the brute-force store's under
// each probe. The machine's load inflates wall times; CPU ratios are printed
// beside them, with x_cpu's floor (below). --quick: cubes-wall on
// camera:64x64 only, N = 32 and 64. --repeat R (default 1): the two bakes of
// each case alternate R times and every time is the median of its R runs
// (the stores and errors are the last runs'); the brute-force bake's speed
// drifts with the machine's state from one run to the next more than the
// refined one's does. --fixed-depth: the refined bake also runs with
// --column-mode 2d and full in the same turns, and a second table prints
// their x_cpu and x_cols: the column stage without any depth search.
// The last line is one JSON object with every number.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench/bake_run.h"
#include "core/bake/bake_params_io.h"
#include "core/transport/refined_row.h"
#include "core/transport/transport_row.h"
#include "driver/eval/reference_measure.h"
#include "worker/tiles/bake_context.h"

namespace wavebake {
namespace {

[[noreturn]] void Die(const std::string& what) {
  std::fprintf(stderr, "bench_refine_bake: %s\n", what.c_str());
  std::exit(1);
}

template <typename T>
T Value(absl::StatusOr<T> v) {
  if (!v.ok()) Die(v.status().ToString());
  return *std::move(v);
}

struct Case {
  std::string name, scene, layout;
};

struct Config {
  std::filesystem::path work;
  bool quick = false;
  int workers = 2;
  int repeat = 1;
  bool fixed_depth = false;
  int bake_res = 64, rays_res = 128;
};

std::vector<Case> Cases(const Config& c) {
  const std::string models = std::string(WB_SHARED_DATA) + "/models/";
  if (c.quick) return {{"cubes-wall", "builtin:cubes-wall", "camera:64x64"}};
  return {{"cubes-wall", "builtin:cubes-wall", "camera:256x256"},
          {"spot", models + "spot.obj", "hilbert:64x64"},
          {"bunny", models + "bunny.obj", "hilbert:64x64"}};
}

const char* kProbes[] = {"grace", "pisa"};

std::string Probe(const char* name) {
  return std::string(WB_SHARED_DATA) + "/probes/" + name + ".hdr";
}

// Refined rays over every sample (rows traced and dropped) and brute force's
// count for the same samples, at one light resolution.
std::pair<uint64_t, uint64_t> CountRays(const Case& c, int light_res, int threads) {
  BakeParams p;
  p.light_res = light_res;
  p.layout = c.layout;
  const std::unique_ptr<BakeContext> ctx = Value(MakeBakeContext(c.scene, p));
  std::atomic<size_t> next{0};
  std::atomic<uint64_t> refined{0}, brute{0};
  auto work = [&] {
    RefineScratch scratch;
    std::vector<float> row(ctx->cubemap.size());
    TransportStats stats;
    uint64_t brute_rays = 0;
    for (size_t s; (s = next.fetch_add(1)) < size_t(ctx->samples.size());) {
      RefinedTransportRow(ctx->caster, ctx->cubemap, ctx->jitter, *ctx->refine,
                          ctx->samples.position[s], ctx->samples.normal[s], ctx->epsilon, row,
                          &stats, scratch);
      brute_rays += BruteForceRays(ctx->cubemap, ctx->jitter, ctx->samples.normal[s]);
    }
    refined += stats.rays_traced;
    brute += brute_rays;
  };
  {
    std::vector<std::jthread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
  }
  return {refined.load(), brute.load()};
}

// The bakes of a case, in the order they alternate: brute force and
// refinement (the adaptive column stage), then with --fixed-depth the refined
// bake at each fixed depth (`2d`: the cells, `full`: the deepest), whose
// column stage has no depth search: what the column stage and FINALIZE would
// cost however cheap the search became.
struct Variant {
  const char* name;
  bool refine;
  ColumnMode mode;
};
constexpr Variant kBrute{"brute", false, ColumnMode::kAdaptive};
constexpr Variant kRefined{"refined", true, ColumnMode::kAdaptive};
constexpr Variant kFixedDepths[] = {{"refined-2d", true, ColumnMode::k2d},
                                    {"refined-full", true, ColumnMode::kFull}};

nlohmann::json RunCase(const Case& c, const Config& config) {
  nlohmann::json j = {{"case", c.name}, {"scene", c.scene}, {"layout", c.layout}};
  std::vector<Variant> variants = {kBrute, kRefined};
  if (config.fixed_depth)
    variants.insert(variants.end(), std::begin(kFixedDepths), std::end(kFixedDepths));
  std::vector<std::filesystem::path> stores(variants.size());
  std::vector<std::vector<bench::PhasedBake>> runs(variants.size());
  // The bakes in turn, --repeat times: all see the same drift of the
  // machine, and each time is the median of its runs.
  for (int repeat = 0; repeat < config.repeat; ++repeat) {
    for (size_t v = 0; v < variants.size(); ++v) {
      BakeParams p;
      p.light_res = config.bake_res;
      p.layout = c.layout;
      p.refine = variants[v].refine;
      p.column_mode = variants[v].mode;
      stores[v] = config.work / (c.name + "-" + variants[v].name + ".wbk");
      std::filesystem::remove_all(stores[v]);
      const bench::PhasedBake& run =
          runs[v].emplace_back(Value(bench::RunPhasedBake(c.scene, p, stores[v], config.workers)));
      std::fprintf(stderr, "%s N=%d %s: %lld rays, %.1f s wall (%.1f s CPU)\n", c.name.c_str(),
                   config.bake_res, variants[v].name, static_cast<long long>(run.rays),
                   run.total.wall, run.total.cpu);
    }
  }
  std::vector<bench::PhasedBake> bakes(variants.size());
  for (size_t v = 0; v < variants.size(); ++v) {
    bakes[v] = bench::MedianBake(runs[v]);
    j[variants[v].name] = bakes[v].ToJson();
  }
  j["repeat"] = config.repeat;
  j["x_rays"] = double(bakes[1].rays) / bakes[0].rays;
  j["x_wall"] = bakes[1].total.wall / bakes[0].total.wall;
  j["x_cpu"] = bakes[1].total.cpu / bakes[0].total.cpu;
  // What x_cpu would be if the refined baking phase were free: the phases
  // that do not shrink with the rays (setup, the column stage, FINALIZE) bound
  // the whole-bake ratio from below.
  const bench::PhasedBake& r = bakes[1];
  j["x_cpu_floor"] = (r.setup.cpu + r.transforming.cpu + r.finalizing.cpu) / bakes[0].total.cpu;
  // The column stage and FINALIZE of the refined bake against the whole
  // brute-force bake's CPU (target <= 0.15 on spot and the bunny at N = 64).
  j["x_cols_cpu"] = (r.transforming.cpu + r.finalizing.cpu) / bakes[0].total.cpu;
  for (size_t v = 2; v < variants.size(); ++v) {
    const bench::PhasedBake& f = bakes[v];
    j["fixed_depth"][std::string(ToString(variants[v].mode))] = {
        {"x_cpu", f.total.cpu / bakes[0].total.cpu},
        {"x_cols_cpu", (f.transforming.cpu + f.finalizing.cpu) / bakes[0].total.cpu},
        {"store_bytes", f.store_bytes}};
    std::filesystem::remove_all(stores[v]);
  }
  BakeParams layout;
  layout.layout = c.layout;
  for (const char* probe : kProbes) {
    const auto measure =
        Value(driver::ReferenceMeasure::Create(c.scene, layout, Probe(probe), 0.002));
    const int terms[] = {256};
    const double brute = Value(measure->StoreErrors(stores[0], terms))[0];
    const double refined = Value(measure->StoreErrors(stores[1], terms))[0];
    j["error"][probe] = {{"brute", brute},
                         {"refined", refined},
                         {"delta", refined - brute},
                         {"reference_rel_se", measure->reference().rel_se}};
    std::fprintf(stderr, "%s under %s: brute %.5f, refined %.5f (reference rel SE %.5f)\n",
                 c.name.c_str(), probe, brute, refined, measure->reference().rel_se);
  }
  for (size_t v = 0; v < 2; ++v) std::filesystem::remove_all(stores[v]);
  const auto [refined_rays, brute_rays] = CountRays(c, config.rays_res, config.workers);
  j["rays_at"] = {{"light_res", config.rays_res},
                  {"refined", refined_rays},
                  {"brute", brute_rays},
                  {"x_rays", double(refined_rays) / brute_rays}};
  return j;
}

const char* Mark(bool ok) { return ok ? "  ok" : "  MISSED"; }

void PrintTable(const nlohmann::json& cases, const Config& config) {
  const double whole = config.bake_res >= 128 ? 0.25 : 0.35;
  std::printf("\n%-11s %8s %8s %8s %8s %8s %8s  %-9s %-9s  %s\n", "case", "x_rays", "x_rays",
              "x_wall", "x_cpu", "x_cpu", "x_cols", "d_err", "d_err", "");
  std::printf("%-11s %8s %8s %8s %8s %8s %8s  %-9s %-9s\n", "",
              ("N=" + std::to_string(config.bake_res)).c_str(),
              ("N=" + std::to_string(config.rays_res)).c_str(), "", "", "floor", "cpu", "grace",
              "pisa");
  for (const nlohmann::json& c : cases) {
    const double xr = c["x_rays"], xr2 = c["rays_at"]["x_rays"], xw = c["x_wall"], xc = c["x_cpu"];
    const double xf = c["x_cpu_floor"], xcols = c["x_cols_cpu"];
    const double dg = c["error"]["grace"]["delta"], dp = c["error"]["pisa"]["delta"];
    const bool cols_goal = c["case"] != "cubes-wall";  // the goal names spot and the bunny
    std::printf("%-11s %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f  %+.5f  %+.5f %s%s%s%s%s%s\n",
                c["case"].get<std::string>().c_str(), xr, xr2, xw, xc, xf, xcols, dg, dp,
                Mark(xr <= 0.25), Mark(xr2 <= 0.12), Mark(xw <= whole), Mark(xc <= whole),
                cols_goal ? Mark(xcols <= 0.15) : "  -", Mark(dg <= 0.002 && dp <= 0.002));
  }
  std::printf(
      "targets (marks in this order): x_rays <= 0.25 (N=%d), <= 0.12 (N=%d); x_wall <= %.2f; "
      "x_cpu <= %.2f; x_cols <= 0.15 (spot, bunny); d_err <= +0.002\n",
      config.bake_res, config.rays_res, whole, whole);
  std::printf(
      "x_cpu floor: the refined bake's setup, column stage and FINALIZE CPU over the\n"
      "brute-force bake's CPU, what x_cpu would be with a free baking phase; x_cols: the\n"
      "refined bake's column stage and FINALIZE CPU over the brute-force bake's CPU\n");
  if (!config.fixed_depth) return;
  std::printf("\nwithout a depth search (--fixed-depth): the refined bake at one depth\n");
  std::printf("%-11s %-13s %8s %8s %12s\n", "case", "column mode", "x_cpu", "x_cols", "bytes");
  for (const nlohmann::json& c : cases) {
    for (const auto& [mode, f] : c["fixed_depth"].items()) {
      const double xc = f["x_cpu"], xcols = f["x_cols_cpu"];
      std::printf("%-11s %-13s %8.3f %8.3f %12lld\n", c["case"].get<std::string>().c_str(),
                  mode.c_str(), xc, xcols, f["store_bytes"].get<long long>());
    }
  }
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  constexpr const char* kUsage =
      "usage: bench_refine_bake WORK_DIR [--quick] [--workers W] [--bake-res N] [--repeat R] "
      "[--fixed-depth]";
  wavebake::Config config;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      config.quick = true;
    } else if (arg == "--bake-res" && i + 1 < argc) {
      config.bake_res = std::atoi(argv[++i]);
    } else if (arg == "--workers" && i + 1 < argc) {
      config.workers = std::atoi(argv[++i]);
    } else if (arg == "--fixed-depth") {
      config.fixed_depth = true;
    } else if (arg == "--repeat" && i + 1 < argc) {
      config.repeat = std::atoi(argv[++i]);
    } else if (!arg.empty() && arg[0] != '-' && config.work.empty()) {
      config.work = arg;
    } else {
      wavebake::Die(kUsage);
    }
  }
  if (config.work.empty() || config.workers < 1 || config.repeat < 1) wavebake::Die(kUsage);
  if (config.quick) config.bake_res = 32, config.rays_res = 64;
  if (!config.quick) config.rays_res = std::max(128, config.bake_res);
  std::filesystem::create_directories(config.work);
  nlohmann::json cases = nlohmann::json::array();
  for (const wavebake::Case& c : wavebake::Cases(config))
    cases.push_back(wavebake::RunCase(c, config));
  wavebake::PrintTable(cases, config);
  std::printf("%s\n", nlohmann::json{{"cases", cases}}.dump().c_str());
  return 0;
}
