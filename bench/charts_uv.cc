// The data behind docs/RESULTS.md chart 7: what the lightmap (uv) layout
// buys the adaptive column transform on a real mesh. spot.obj is traced once
// per layout — hilbert:64x64 (its 3225 vertices) and uv at 128², 256², 512²
// — and each compression setting reruns only TRANSFORM_COLUMNS × groups and
// FINALIZE on that staging (as bench/charts_data.cc does):
//   uv_size.csv   2d and adaptive over a range of targets, per layout;
//   uv_fill.csv   the uncovered-texel fills (core/columns/uncovered_fill.h) at
//                 target 0.01, adaptive and full depth, per uv size.
//
//   build/bench_charts_uv OUT_DIR [--quick] [--threads T] [--sizes 128,256,512]
//                         [--work DIR]   (keep the traced stagings in DIR and
//                                         reuse them on the next run)
//                         [--fills-only]  (uv_fill.csv alone)
// A plain main(), linked with Google Benchmark like every bench/*.cc.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/chart_util.h"
#include "core/bake/bake_params.h"
#include "core/bake/bake_params_io.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "worker/columns/finalize.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

using charts::Check;
using charts::Csv;
using charts::Die;
using charts::RunTasksOrDie;
using charts::SecondsSince;
using charts::Value;

struct RunConfig {
  std::filesystem::path out_dir, work_dir;
  bool keep_work = false, quick = false, fills_only = false;
  int threads = 2;
  std::vector<int> sizes{128, 256, 512};
};

std::string Spot() { return WB_SHARED_DATA "/models/spot.obj"; }

// Traces `layout` into a staging store under the work dir, unless a finished
// trace of the same layout and N is there already (its marker file).
std::filesystem::path Stage(const std::string& layout, int light_res, const RunConfig& run) {
  std::string name = layout;
  for (char& c : name)
    if (c == ':' || c == ',') c = '-';
  const std::filesystem::path store =
      run.work_dir / (name + "-N" + std::to_string(light_res) + ".wbk");
  if (std::filesystem::exists(store / "traced")) return store;
  std::filesystem::remove_all(store);
  BakeParams p;
  p.light_res = light_res;
  p.layout = layout;
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<BakeContext> ctx = Value(MakeBakeContext(Spot(), p));
  Check(CreateStaging(ctx->plan, store));
  RunTasksOrDie(ctx->plan.tiles(), run.threads,
                [&](int t) { return BakeTile(*ctx, store, t, nullptr); });
  FILE* marker = std::fopen((store / "traced").c_str(), "w");
  if (marker != nullptr) std::fclose(marker);
  std::fprintf(stderr, "traced %s N=%d: %zu samples, %.1f s\n", layout.c_str(), light_res,
               static_cast<size_t>(ctx->samples.size()), SecondsSince(start));
  return store;
}

struct Compressed {
  nlohmann::json attrs;
  double seconds = 0;
};

Compressed Compress(const std::filesystem::path& store, const BakeParams& p, const RunConfig& run) {
  for (const char* name : {store::kTransport, store::kSamples, ".zattrs"})
    std::filesystem::remove_all(store / name);
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<BakeContext> ctx = Value(MakeBakeContext(Spot(), p));
  RunTasksOrDie(ctx->plan.groups, run.threads,
                [&](int g) { return TransformColumns(*ctx, store, g, nullptr); });
  Check(Finalize(*ctx, store, {.keep_staging = true}));
  Compressed c{Value(ReadStoreInfo(store)).attrs, SecondsSince(start)};
  const nlohmann::json& stats = c.attrs["stats"];
  std::fprintf(stderr, "  %s %s target %.3f: %llu bytes, nnz %lld, depths %s, %.1f s\n",
               p.layout.c_str(), std::string(ToString(p.column_mode)).c_str(), p.target_error,
               static_cast<unsigned long long>(stats["bytes"]["transport"].get<uint64_t>()),
               static_cast<long long>(stats["nnz"].get<int64_t>()),
               stats["depth_histogram"].dump().c_str(), c.seconds);
  return c;
}

void Row(Csv& csv, const std::string& kind, int side, const BakeParams& p, const std::string& fill,
         const Compressed& c) {
  const nlohmann::json& s = c.attrs.at("stats");
  const int64_t samples = c.attrs.at("S").get<int64_t>();
  const uint64_t bytes = s.at("bytes").at("transport").get<uint64_t>();
  csv.Row(kind, side, std::string(ToString(p.column_mode)), fill, p.target_error, samples,
          s.at("nnz").get<int64_t>(), bytes, double(bytes) / double(samples),
          s.at("matrix_rel_rms").get<double>(), c.seconds);
}

void Run(const RunConfig& run) {
  std::filesystem::create_directories(run.out_dir);
  std::filesystem::create_directories(run.work_dir);
  const int n = run.quick ? 8 : 32;
  const std::vector<double> targets =
      run.quick ? std::vector<double>{0.01} : std::vector<double>{0.005, 0.01, 0.02, 0.05};
  Csv size_csv(run.out_dir / "uv_size.csv",
               "layout,side,mode,fill,target,samples,nnz,transport_bytes,bytes_per_sample,"
               "matrix_rel_rms,seconds");
  Csv fill_csv(run.out_dir / "uv_fill.csv",
               "layout,side,mode,fill,target,samples,nnz,transport_bytes,bytes_per_sample,"
               "matrix_rel_rms,seconds");
  struct Case {
    std::string kind;
    int side;
  };
  std::vector<Case> cases;
  if (!run.fills_only) cases.push_back({"hilbert", 64});
  for (int side : run.sizes) cases.push_back({"uv", side});
  for (const Case& c : cases) {
    const std::string layout = c.kind + ":" + std::to_string(c.side) + "x" + std::to_string(c.side);
    const std::filesystem::path store = Stage(layout, n, run);
    // The big lightmap only at the default target: its column stage is the slow part.
    const bool big = c.side >= 512;
    for (ColumnMode mode : {ColumnMode::k2d, ColumnMode::kAdaptive}) {
      for (double target : targets) {
        if (run.fills_only) continue;
        if (big && target != 0.01) continue;
        BakeParams p;
        p.light_res = n;
        p.layout = layout;
        p.column_mode = mode;
        p.target_error = target;
        Row(size_csv, c.kind, c.side, p, c.kind == "uv" ? "push-pull" : "zero",
            Compress(store, p, run));
      }
    }
    if (c.kind != "uv") continue;
    for (ColumnMode mode : {ColumnMode::kAdaptive, ColumnMode::kFull}) {
      for (const char* fill : {"zero", "push-pull", "dilate"}) {
        if (big && mode == ColumnMode::kFull) continue;
        BakeParams p;
        p.light_res = n;
        p.layout = layout + ",fill=" + fill;
        p.column_mode = mode;
        Row(fill_csv, c.kind, c.side, p, fill, Compress(store, p, run));
      }
    }
  }
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  wavebake::charts::program = "bench_charts_uv";
  const char* usage =
      "usage: bench_charts_uv OUT_DIR [--quick] [--threads T] [--sizes 128,256,512] [--work DIR] "
      "[--fills-only]";
  wavebake::RunConfig run;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      run.quick = true;
    } else if (arg == "--fills-only") {
      run.fills_only = true;
    } else if (arg == "--threads" && i + 1 < argc) {
      run.threads = std::atoi(argv[++i]);
    } else if (arg == "--sizes" && i + 1 < argc) {
      run.sizes.clear();
      std::stringstream list(argv[++i]);
      for (std::string v; std::getline(list, v, ',');) run.sizes.push_back(std::atoi(v.c_str()));
    } else if (arg == "--work" && i + 1 < argc) {
      run.work_dir = argv[++i];
      run.keep_work = true;
    } else if (!arg.empty() && arg[0] != '-' && run.out_dir.empty()) {
      run.out_dir = arg;
    } else {
      wavebake::Die(usage);
    }
  }
  if (run.out_dir.empty() || run.threads < 1) wavebake::Die(usage);
  if (run.work_dir.empty())
    run.work_dir =
        std::filesystem::temp_directory_path() / ("wavebake-uv-" + std::to_string(::getpid()));
  wavebake::Run(run);
  if (!run.keep_work) std::filesystem::remove_all(run.work_dir);
  return 0;
}
