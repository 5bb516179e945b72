// The data behind docs/RESULTS.md: sweeps of the real pipeline,
// one CSV per chart, written into the directory given on the command line.
//
//   build/bench_charts_data OUT_DIR [--quick] [--light-res-only] [--threads T]
//
// Each (scene, layout, light resolution) is traced once (worker/tiles/recode.h
// TraceStaging); every compression setting then reruns only the column
// stage on that trace (worker/tiles/recode.h Recode), so a sweep costs one trace
// plus one column stage per point. The x
// axis of charts 1, 5 and 6 is the store's own stats.matrix_rel_rms =
// sqrt(Σ dropped + quantization energy / Σ energy) (worker/columns/store_stats.h):
// the relative Frobenius error of the whole matrix, a summary that depends on
// no lighting. Chart 1 adds the relighting error each store has under both
// probes of ../shared/data against the dense T (the error users see), and
// chart 2 brute force against visibility refinement (rays, time) and the
// relighting error under a probe against the independent Monte-Carlo
// reference (runtime/reference/reference.h). A plain main(): the file is
// linked with Google Benchmark like every bench/*.cc but uses none of it.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "bench/chart_util.h"
#include "core/bake/bake_params.h"
#include "core/bake/bake_params_io.h"
#include "core/directions/cubemap.h"
#include "driver/eval/reference_measure.h"
#include "driver/relight/staged_relight.h"
#include "runtime/env/env_map.h"
#include "runtime/env/env_resample.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/store_relight.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/recode.h"

namespace wavebake {
namespace {

using charts::Check;
using charts::Csv;
using charts::Die;
using charts::SecondsSince;
using charts::Value;

struct SceneCase {
  std::string name;    // short label for the CSVs
  std::string spec;    // builtin:NAME or a mesh path
  std::string layout;  // DESIGN.md §1 "Spatial layout"
};

// Three kinds of spatial layout: a camera layout, the bunny on a Hilbert
// layout, and a regular-grid mesh.
std::vector<SceneCase> ChartScenes() {
  return {{"cubes-wall", "builtin:cubes-wall", "camera:64x64"},
          {"bunny", std::string(WB_SHARED_DATA) + "/models/bunny.obj", "hilbert:64x64"},
          {"cylinder-bump", "builtin:cylinder-bump", "grid"}};
}

struct RunConfig {
  std::filesystem::path out_dir, work_dir;
  bool quick = false;
  bool light_res_only = false;  // chart 2 alone (bake_time.csv)
  int threads = 2;
};

// One traced (scene, layout, N, refinement): a trace ready for column stages.
struct Staged {
  SceneCase scene;
  BakeParams base;
  std::unique_ptr<BakeContext> ctx;  // the trace's
  std::filesystem::path store;       // the trace; the latest Compress's store beside it
  double bake_seconds = 0;
  uint64_t rays = 0;
  std::filesystem::path coded() const { return store.string() + "-coded.wbk"; }
};

Staged BakeStaging(const SceneCase& scene, int light_res, const RunConfig& run,
                   bool refine = true) {
  Staged s;
  s.scene = scene;
  s.base.light_res = light_res;
  s.base.layout = scene.layout;
  s.base.refine = refine;
  s.store = run.work_dir / (scene.name + "-N" + std::to_string(light_res) +
                            (refine ? "-refined" : "-brute") + ".trace");
  std::filesystem::remove_all(s.store);
  const auto start = std::chrono::steady_clock::now();
  s.ctx = Value(MakeBakeContext(scene.spec, s.base));
  s.rays = Value(TraceStaging(*s.ctx, s.store, {.threads = run.threads}));
  s.bake_seconds = SecondsSince(start);
  std::fprintf(stderr, "traced %s N=%d (%s): %.1f s, %.1f Mrays\n", scene.name.c_str(), light_res,
               refine ? "refined" : "brute force", s.bake_seconds, s.rays / 1e6);
  return s;
}

// What one compression setting produced, from the store's .zattrs; the store
// is at staged.coded() until the next Compress.
struct Compressed {
  nlohmann::json stats;  // attrs["stats"]
  int bits = 0;
  double seconds = 0;  // TRANSFORM_COLUMNS × groups + FINALIZE
};

Compressed Compress(const Staged& staged, const BakeParams& params, const RunConfig& run) {
  std::filesystem::remove_all(staged.coded());
  const auto start = std::chrono::steady_clock::now();
  BakeParams p = params;
  p.refine = staged.base.refine;
  const std::unique_ptr<BakeContext> ctx = Value(MakeBakeContext(staged.scene.spec, p));
  Check(Recode(*ctx, staged.store, staged.coded(), {.threads = run.threads}));
  Compressed c;
  c.seconds = SecondsSince(start);
  const StoreInfo info = Value(ReadStoreInfo(staged.coded()));
  c.stats = info.attrs.at("stats");
  c.bits = info.bits;
  return c;
}

void Drop(const Staged& staged) {
  std::filesystem::remove_all(staged.store);
  std::filesystem::remove_all(staged.coded());
}

// Chart 1 "under both probes": each store relit with all its wavelet lights
// under each probe of ../shared/data, against the dense T of the same trace
// relit under that probe (driver/relight/staged_relight.h):
// the relighting error compression alone adds for that lighting, which the
// matrix error bounds for all lightings at once.
struct ProbeCase {
  std::string name;
  EnvMap env;
  std::vector<float> dense;  // [cells*3] the dense T relit, × albedo
};

std::vector<ProbeCase> DenseUnderProbes(const Staged& staged) {
  std::vector<ProbeCase> probes;
  for (const char* name : {"grace", "pisa"}) {
    ProbeCase p{
        name, Value(LoadEnvMap(std::string(WB_SHARED_DATA) + "/probes/" + name + ".hdr")), {}};
    const std::vector<float> cube = ResampleToCubemap(p.env, Cubemap(staged.base.light_res));
    // The trace's own dense T (refined or brute force, as the store's).
    p.dense = Value(driver::RelightStaging(*staged.ctx, staged.store, cube));
    probes.push_back(std::move(p));
  }
  return probes;
}

// The store's relighting error under each probe, in `probes` order.
std::vector<double> ProbeErrors(const Staged& staged, const std::vector<ProbeCase>& probes) {
  OpenedStore store = Value(OpenStore(staged.coded()));
  const int all_lights = 6 * staged.base.light_res * staged.base.light_res;
  std::vector<double> errors;
  for (const ProbeCase& p : probes)
    errors.push_back(
        CompareToReference(Value(RelightImage(store, p.env, all_lights)), p.dense).rel_rms);
  return errors;
}

std::string Name(ColumnMode m) { return std::string(ToString(m)); }
std::string Name(WaveletFilter f) { return std::string(ToString(f)); }

void SizeRow(const Staged& staged, const std::vector<ProbeCase>& probes, const BakeParams& p,
             const Compressed& c, Csv& size_csv) {
  const nlohmann::json& bytes = c.stats.at("bytes");
  const std::vector<double> probe_errors = ProbeErrors(staged, probes);
  size_csv.Row(staged.scene.name, Name(p.column_mode), Name(p.column_filter),
               std::string(ToString(p.level_scaling)), p.target_error,
               c.stats.at("nnz").get<int64_t>(), bytes.at("transport").get<uint64_t>(),
               bytes.at("arrays").at("transport/indices").get<uint64_t>(),
               bytes.at("arrays").at("transport/data").get<uint64_t>(),
               bytes.at("raw_float32").get<uint64_t>(), c.bits,
               c.stats.at("matrix_rel_rms").get<double>(), c.seconds, probe_errors[0],
               probe_errors[1]);
}

// Chart 1 (4D paper Fig. 7) and chart 6 (Fig. 8): bytes and kept
// coefficients against matrix error, per mode × column filter × target with
// the default (uniform) value coding, plus adaptive Haar with the paper's 2^l
// level scaling (4D paper §4.3) as the baseline; the adaptive Haar runs also give
// the mean depth by row level.
void SweepSizeAndDepth(const Staged& staged, const RunConfig& run, Csv& size_csv, Csv& depth_csv) {
  const std::vector<ProbeCase> probes = DenseUnderProbes(staged);
  const std::vector<double> targets = run.quick ? std::vector<double>{0.01, 0.05}
                                                : std::vector<double>{0.003, 0.01, 0.02, 0.05, 0.1};
  for (double target : targets) {
    BakeParams p = staged.base;
    p.target_error = target;
    p.level_scaling = LevelScaling::kPaper;
    SizeRow(staged, probes, p, Compress(staged, p, run), size_csv);
  }
  for (ColumnMode mode : {ColumnMode::k2d, ColumnMode::kFull, ColumnMode::kAdaptive}) {
    for (WaveletFilter filter : {WaveletFilter::kHaar, WaveletFilter::kLeGall53}) {
      for (double target : targets) {
        BakeParams p = staged.base;
        p.column_mode = mode;
        p.column_filter = filter;
        p.target_error = target;
        const Compressed c = Compress(staged, p, run);
        SizeRow(staged, probes, p, c, size_csv);
        if (mode != ColumnMode::kAdaptive || filter != WaveletFilter::kHaar) continue;
        const nlohmann::json& mean = c.stats.at("mean_depth_by_row_level");
        for (size_t level = 0; level < mean.size(); ++level)
          depth_csv.Row(staged.scene.name, target, level, mean[level].get<double>());
      }
    }
  }
}

// Chart 5: matrix error against fixed quantization bits (each column's max
// mapped to the largest b-bit code), and bits auto (bits 0 in the CSV: the
// matrix-wide error-budgeted step) for comparison.
void SweepBits(const Staged& staged, const RunConfig& run, Csv& csv) {
  std::vector<int> fixed;
  for (int bits = 4; bits <= 12; bits += run.quick ? 4 : 1) fixed.push_back(bits);
  fixed.push_back(0);
  for (ColumnMode mode : {ColumnMode::k2d, ColumnMode::kAdaptive}) {
    for (int bits : fixed) {
      BakeParams p = staged.base;
      p.column_mode = mode;
      p.target_error = 0.01;
      p.bits = bits;
      const Compressed c = Compress(staged, p, run);
      csv.Row(staged.scene.name, Name(mode), p.target_error, bits,
              c.stats.at("matrix_rel_rms").get<double>(),
              c.stats.at("bytes").at("transport").get<uint64_t>(),
              c.stats.at("nnz").get<int64_t>());
    }
  }
}

// Chart 2: brute force against visibility refinement per N — rays, trace
// time, column stage, size, matrix error — and the relighting error under
// `env` against the independent reference (driver/eval/reference_measure.h,
// traced once): the trace's own dense T at N (discretization alone, relit
// from the trace: driver/relight/staged_relight.h) and the store with all 6N²
// wavelet lights and with the runtime's default 256 — what `eval
// --reference` reports, and what `bake --auto` chooses N by.
void SweepLightRes(const SceneCase& scene, const std::string& env, const RunConfig& run, Csv& csv) {
  const std::vector<int> resolutions =
      run.quick ? std::vector<int>{8, 16} : std::vector<int>{8, 16, 32, 64, 128};
  BakeParams base;
  base.layout = scene.layout;
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<driver::ReferenceMeasure> measure =
      Value(driver::ReferenceMeasure::Create(scene.spec, base, env, run.quick ? 0.01 : 0.002));
  std::fprintf(stderr, "reference %s: rel SE %.4f, %.1f s\n", scene.name.c_str(),
               measure->reference().rel_se, SecondsSince(start));
  for (int n : resolutions) {
    for (bool refine : {false, true}) {
      const Staged staged = BakeStaging(scene, n, run, refine);
      BakeParams p = staged.base;  // adaptive, haar, target 0.01, bits auto
      const Compressed c = Compress(staged, p, run);
      const auto dense_start = std::chrono::steady_clock::now();
      const double dense = Value(measure->StagingError(*staged.ctx, staged.store));
      const double dense_seconds = SecondsSince(dense_start);
      const int terms[] = {6 * n * n, 256};
      const std::vector<double> store = Value(measure->StoreErrors(staged.coded(), terms));
      csv.Row(scene.name, refine ? "refined" : "brute", n, staged.bake_seconds, staged.rays,
              c.seconds, c.stats.at("nnz").get<int64_t>(),
              c.stats.at("bytes").at("transport").get<uint64_t>(),
              c.stats.at("matrix_rel_rms").get<double>(), c.bits, run.threads,
              std::filesystem::path(env).filename().string(), measure->reference().rel_se, dense,
              store[0], store[1], dense_seconds);
      Drop(staged);
    }
  }
}

void Run(const RunConfig& run) {
  std::filesystem::create_directories(run.out_dir);
  std::filesystem::create_directories(run.work_dir);
  const auto start = std::chrono::steady_clock::now();
  Csv res_csv(run.out_dir / "bake_time.csv",
              "scene,visibility,light_res,bake_seconds,rays,column_seconds,nnz,transport_bytes,"
              "matrix_rel_rms,bits,threads,env,reference_rel_se,dense_ref_rel_rms,"
              "store_ref_rel_rms,store_ref_rel_rms_256,dense_seconds");
  // With --light-res-only the other charts' CSVs are left as they are.
  if (!run.light_res_only) {
    Csv size_csv(run.out_dir / "size_error.csv",
                 "scene,mode,filter,coding,target,nnz,transport_bytes,indices_bytes,data_bytes,"
                 "raw_bytes,bits,matrix_rel_rms,seconds,grace_rel_rms,pisa_rel_rms");
    Csv depth_csv(run.out_dir / "depth_by_level.csv", "scene,target,row_level,mean_depth");
    Csv bits_csv(run.out_dir / "bits_error.csv",
                 "scene,mode,target,bits,matrix_rel_rms,transport_bytes,nnz");
    const int light_res = run.quick ? 8 : 32;
    for (const SceneCase& scene : ChartScenes()) {
      const Staged staged = BakeStaging(scene, light_res, run);
      SweepSizeAndDepth(staged, run, size_csv, depth_csv);
      if (scene.name == "cubes-wall") SweepBits(staged, run, bits_csv);
      Drop(staged);
    }
  }
  // The bunny under grace.hdr: a mesh layout under a probe with small,
  // very bright sources, where N matters (docs/RESULTS.md, chart 2).
  SweepLightRes(ChartScenes()[1], std::string(WB_SHARED_DATA) + "/probes/grace.hdr", run, res_csv);
  std::fprintf(stderr, "bench_charts_data: done in %.0f s\n", SecondsSince(start));
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  wavebake::charts::program = "bench_charts_data";
  wavebake::RunConfig run;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      run.quick = true;
    } else if (arg == "--light-res-only") {
      run.light_res_only = true;
    } else if (arg == "--threads" && i + 1 < argc) {
      run.threads = std::atoi(argv[++i]);
    } else if (!arg.empty() && arg[0] != '-' && run.out_dir.empty()) {
      run.out_dir = arg;
    } else {
      wavebake::Die("usage: bench_charts_data OUT_DIR [--quick] [--light-res-only] [--threads T]");
    }
  }
  if (run.out_dir.empty() || run.threads < 1)
    wavebake::Die("usage: bench_charts_data OUT_DIR [--quick] [--light-res-only] [--threads T]");
  run.work_dir =
      std::filesystem::temp_directory_path() / ("wavebake-charts-" + std::to_string(::getpid()));
  wavebake::Run(run);
  std::filesystem::remove_all(run.work_dir);
  return 0;
}
