// The runtime charts of docs/RESULTS.md, on real stores (bench/charts.sh runs it
// after bench_charts_data):
//
//   build/bench_charts_runtime OUT_DIR [--quick] [--threads T]
//
// Chart 3, relight_time.csv (4D paper Fig. 9): seconds per Eq. 8 frame
// (runtime/relight/relighter.h) against the number of wavelet lights n, for a 2d and
// an adaptive store of the same scene baked at the same target error (their
// measured matrix errors are in the CSV). Time is the median thread CPU time
// of several frames (the machine is shared; CPU time is what the frame
// costs; fastest of three runs of each frame), lighting excluded. `touched` is the stored
// coefficients of the chosen columns, the sparse adds Eq. 8 does.
//
// Chart 4, rotation_error.csv (Overbeck Fig. 6.2): error per frame of a
// rotating environment for non-incremental, basic incremental (ch. 4) and
// per-band incremental (§6.2.2) lighting with the same n, at a few rotation
// speeds. Two errors per frame: the relit image's relative RMS against the
// same frame relit with every wavelet light (what `wavebake relight
// --rotate-sequence` writes to errors.csv), and the lighting's area-weighted
// relative L1 error ‖L − L̃‖ / ‖L‖ (Ω-weighted as in §6.2.2), the thesis'
// metric. A plain main(), linked with Google Benchmark like every bench/*.cc.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "bench/chart_util.h"
#include "core/bake/bake_params.h"
#include "core/bake/bake_params_io.h"
#include "driver/bake/embedded_bake.h"
#include "driver/jobs/job_query.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/incremental.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/relighter.h"
#include "runtime/relight/row_basis.h"
#include "storage/store/store_reader.h"

namespace wavebake {
namespace {

using charts::Csv;
using charts::Die;
using charts::Value;

double ThreadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

struct RunConfig {
  std::filesystem::path out_dir, work_dir;
  bool quick = false;
  int threads = 2;
};

// cubes-wall: sharp shadows of several boxes on a wall and a floor, the
// camera scene of chart 1. Full: camera:64x64, N = 32; quick: 32x32, N = 8.
constexpr const char* kScene = "builtin:cubes-wall";
constexpr double kTarget = 0.01;

struct Store {
  std::string mode;
  CompressedColumns columns;
  SampleSet samples;
  double matrix_rel_rms = 0;
};

Store BakeStore(ColumnMode mode, const RunConfig& run) {
  BakeParams p;
  p.layout = run.quick ? "camera:32x32" : "camera:64x64";
  p.light_res = run.quick ? 8 : 32;
  p.column_mode = mode;
  p.target_error = kTarget;
  Store s;
  s.mode = std::string(ToString(mode));
  const std::filesystem::path path = run.work_dir / (s.mode + ".wbk");
  const auto t0 = std::chrono::steady_clock::now();
  const v1::Job job = Value(driver::EmbeddedBake(kScene, p, path, {.workers = run.threads}));
  if (job.phase() != v1::PHASE_DONE) Die(driver::JobOutcome(job));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.columns = Value(ReadTransport(path));
  s.samples = Value(ReadSamples(path));
  s.matrix_rel_rms = Value(ReadStoreInfo(path)).attrs.at("stats").at("matrix_rel_rms");
  std::fprintf(stderr, "baked %s %s N=%d: %.1f s, nnz %lld, matrix_rel_rms %.5f\n", kScene,
               s.mode.c_str(), p.light_res, seconds,
               static_cast<long long>(s.columns.indptr.back()), s.matrix_rel_rms);
  return s;
}

EnvMap Grace() { return Value(LoadEnvMap(std::string(WB_SHARED_DATA) + "/probes/grace.hdr")); }

// grace.hdr and the overlap of its pixels with the stores' cubemap, built
// once for every frame of a sweep.
struct RotatingGrace {
  explicit RotatingGrace(const Relighter& r)
      : env(Grace()),
        projector(
            Value(EnvProjector::Create(env.width, env.height, r.light_res(), r.row_filter()))) {}
  LightingCoefficients At(double degrees) const {
    return Value(projector.Project(Rotated(env, degrees)));
  }
  EnvMap env;
  EnvProjector projector;
};

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Chart 3: one row per (store, n). Frames differ by a small rotation so the
// chosen columns change a little from frame to frame, as in use. The stores
// are timed in turn on the same frame, each frame three times keeping the
// fastest, so both see the same machine load (2 shared cores) and a burst of
// it moves neither the median nor the ratio.
void RelightTime(const std::vector<Store>& stores, const RunConfig& run, Csv& csv) {
  const int frames = run.quick ? 3 : 9, repeats = 3;
  const int max_terms = run.quick ? 256 : 4096;
  std::vector<Relighter> relighters;
  for (const Store& s : stores)
    relighters.push_back(Value(Relighter::Create(s.columns, s.samples)));
  const RotatingGrace grace(relighters[0]);
  std::vector<LightingCoefficients> lighting;
  for (int f = 0; f < frames; ++f) lighting.push_back(grace.At(5.0 * f));
  std::vector<float> image(3 * static_cast<size_t>(relighters[0].cells()));
  for (int n = 16; n <= max_terms; n *= 2) {
    std::vector<std::vector<double>> times(stores.size());
    std::vector<double> touched(stores.size(), 0.0);
    for (const LightingCoefficients& l : lighting) {
      const WaveletLights lights = Value(SelectWaveletLights(l, n));
      for (size_t s = 0; s < stores.size(); ++s) {
        const std::vector<int64_t>& indptr = stores[s].columns.indptr;
        for (const WaveletLight& w : lights.lights)
          touched[s] += indptr[w.column + 1] - indptr[w.column];
        double best = 1e30;
        for (int r = 0; r < repeats; ++r) {
          const double t0 = ThreadSeconds();
          relighters[s].Relight(lights, image);
          best = std::min(best, ThreadSeconds() - t0);
        }
        times[s].push_back(best);
      }
    }
    std::vector<double> median(stores.size());
    for (size_t s = 0; s < stores.size(); ++s) {
      median[s] = Median(times[s]);
      csv.Row(stores[s].mode, n, median[s], touched[s] / frames, stores[s].matrix_rel_rms,
              relighters[s].nonzeros(), relighters[s].width(), relighters[s].light_res());
    }
    std::fprintf(stderr, "relight n=%5d: %s %.3f ms, %s %.3f ms, %s/%s %.2f\n", n,
                 stores[0].mode.c_str(), 1e3 * median[0], stores[1].mode.c_str(), 1e3 * median[1],
                 stores[1].mode.c_str(), stores[0].mode.c_str(), median[1] / median[0]);
  }
}

// ‖L − L̃‖ / ‖L‖, both Σ_m Ω_m Σ_c |·| (the §6.2.2 norm over all bands).
double LightingError(const LightingCoefficients& l, std::span<const float> approx,
                     std::span<const float> support) {
  double num = 0, den = 0;
  for (size_t m = 0; m < support.size(); ++m) {
    for (int c = 0; c < 3; ++c) {
      num += support[m] * std::fabs(l.rgb[3 * m + c] - approx[3 * m + c]);
      den += support[m] * std::fabs(l.rgb[3 * m + c]);
    }
  }
  return num / den;
}

// The non-incremental L̃: the chosen terms, zero elsewhere.
std::vector<float> Approximation(const WaveletLights& lights, size_t size) {
  std::vector<float> a(size, 0.0f);
  for (const WaveletLight& w : lights.lights) {
    for (int c = 0; c < 3; ++c) a[3 * w.column + c] = w.weight[c];
  }
  return a;
}

// Chart 4: one row per (speed, frame, method).
void RotationError(const Store& store, const RunConfig& run, Csv& csv) {
  Relighter relighter = Value(Relighter::Create(store.columns, store.samples));
  const RotatingGrace grace(relighter);
  const std::vector<float> support = SupportSolidAngles(relighter.light_res());
  const int terms = run.quick ? 16 : 64, frames = run.quick ? 6 : 61;
  const std::vector<double> speeds =
      run.quick ? std::vector<double>{10} : std::vector<double>{2, 11, 37};
  const size_t values = 3 * static_cast<size_t>(relighter.cells());
  std::vector<float> full(values), image(values);
  for (double speed : speeds) {
    IncrementalRelighter basic =
        Value(IncrementalRelighter::Create(&relighter, terms, IncrementalPolicy::kBasic));
    IncrementalRelighter per_band =
        Value(IncrementalRelighter::Create(&relighter, terms, IncrementalPolicy::kPerBand));
    double sums[3] = {0, 0, 0};
    for (int f = 0; f < frames; ++f) {
      const LightingCoefficients l = grace.At(speed * f);
      relighter.Relight(AllWaveletLights(l), full);
      const WaveletLights lights = Value(SelectWaveletLights(l, terms));
      relighter.Relight(lights, image);
      const double e_none = CompareToReference(image, full).rel_rms;
      csv.Row(speed, f, speed * f, "none", terms, e_none,
              LightingError(l, Approximation(lights, l.rgb.size()), support), relighter.width(),
              relighter.light_res());
      if (!basic.Frame(l, image).ok()) Die("basic frame");
      const double e_basic = CompareToReference(image, full).rel_rms;
      csv.Row(speed, f, speed * f, "basic", terms, e_basic,
              LightingError(l, basic.approximation(), support), relighter.width(),
              relighter.light_res());
      if (!per_band.Frame(l, image).ok()) Die("per-band frame");
      const double e_per_band = CompareToReference(image, full).rel_rms;
      csv.Row(speed, f, speed * f, "per-band", terms, e_per_band,
              LightingError(l, per_band.approximation(), support), relighter.width(),
              relighter.light_res());
      sums[0] += e_none, sums[1] += e_basic, sums[2] += e_per_band;
    }
    std::fprintf(stderr,
                 "rotation %g deg/frame, %d terms: mean image rel_rms none %.4f basic %.4f "
                 "per-band %.4f\n",
                 speed, terms, sums[0] / frames, sums[1] / frames, sums[2] / frames);
  }
}

void Run(const RunConfig& run) {
  std::filesystem::create_directories(run.out_dir);
  std::filesystem::create_directories(run.work_dir);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Store> stores = {BakeStore(ColumnMode::k2d, run),
                                     BakeStore(ColumnMode::kAdaptive, run)};
  Csv time_csv(run.out_dir / "relight_time.csv",
               "mode,terms,seconds,touched,matrix_rel_rms,nnz,width,light_res");
  RelightTime(stores, run, time_csv);
  Csv rot_csv(run.out_dir / "rotation_error.csv",
              "speed,frame,degrees,method,terms,image_rel_rms,lighting_rel_l1,width,light_res");
  RotationError(stores[1], run, rot_csv);
  std::fprintf(stderr, "bench_charts_runtime: done in %.0f s\n",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  wavebake::charts::program = "bench_charts_runtime";
  wavebake::RunConfig run;
  const char* usage = "usage: bench_charts_runtime OUT_DIR [--quick] [--threads T]";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      run.quick = true;
    } else if (arg == "--threads" && i + 1 < argc) {
      run.threads = std::atoi(argv[++i]);
    } else if (!arg.empty() && arg[0] != '-' && run.out_dir.empty()) {
      run.out_dir = arg;
    } else {
      wavebake::Die(usage);
    }
  }
  if (run.out_dir.empty() || run.threads < 1) wavebake::Die(usage);
  run.work_dir = std::filesystem::temp_directory_path() /
                 ("wavebake-charts-runtime-" + std::to_string(::getpid()));
  wavebake::Run(run);
  std::filesystem::remove_all(run.work_dir);
  return 0;
}
