// Chart 8 of docs/RESULTS.md (bench/charts.sh runs it): glossy relighting of
// a visibility store through the Haar triple product (runtime/
// glossy_relighter.h) against the number of lighting terms and of BRDF terms
// per sample — Vollick & Lessig §6's L² performance against NLA — for
// phong:8, phong:32 and phong:128 under grace.hdr and pisa.hdr, and the
// relight time against both.
//
//   build/bench_charts_glossy OUT_DIR [--quick] [--threads T]
//
// glossy_error.csv: per (env, brdf, lighting terms, BRDF terms) the relit
// image's relative RMS against the independent Monte-Carlo reference traced
// with that BRDF (runtime/reference/reference.h; `ref`), against the same store at
// every term of both (`all`: what the two approximations alone cost), and
// the dense visibility path's error against the reference (`dense`: the
// cubemap's own floor, no Haar basis, runtime/reference/dense_trace.h).
// glossy_time.csv: thread CPU seconds of one frame (one core, fastest of 5)
// per (brdf, lighting terms, BRDF terms), grace.hdr.
// Full: builtin:sphere-plane camera:64x64, N = 32; quick: camera:32x32, N = 8.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/chart_util.h"
#include "core/directions/cubemap.h"
#include "driver/bake/embedded_bake.h"
#include "runtime/env/env_resample.h"
#include "runtime/glossy/glossy_store.h"
#include "runtime/reference/dense_trace.h"
#include "runtime/reference/eval.h"
#include "runtime/reference/reference.h"
#include "runtime/relight/lighting.h"

namespace wavebake {
namespace {

using charts::Csv;
using charts::Value;

struct RunConfig {
  std::filesystem::path out_dir, work_dir;
  bool quick = false;
  int threads = 2;
};

double ThreadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

std::filesystem::path Bake(const RunConfig& run) {
  BakeParams p;
  p.layout = run.quick ? "camera:32x32" : "camera:64x64";
  p.light_res = run.quick ? 8 : 32;
  p.transport = Transport::kVisibility;
  const std::filesystem::path out = run.work_dir / "sphere-plane.wbk";
  const v1::Job job =
      Value(driver::EmbeddedBake("builtin:sphere-plane", p, out, {.workers = run.threads}));
  if (job.phase() != v1::PHASE_DONE)
    throw std::runtime_error("bake of " + out.string() + " failed: " + job.error());
  return out;
}

std::vector<float> Reference(GlossyStore& g, const EnvMap& env, const RayCaster& caster) {
  const SampleSet& s = g.samples();
  std::vector<Vec3> views(s.size());
  for (int c = 0; c < s.cells(); ++c)
    if (s.grid[c] >= 0) views[s.grid[c]] = g.views()[c];
  ReferenceOptions o;
  o.brdf = &g.brdf();
  o.views = views;
  o.epsilon = caster.DefaultEpsilon();
  const ReferenceResult r = Value(ComputeReference(caster, s, env, o));
  std::fprintf(stderr, "  reference %s: rel_se %.4f, %.0f s\n", g.brdf().Name().c_str(), r.rel_se,
               r.seconds);
  return r.rgb;
}

void Run(const RunConfig& run) {
  std::filesystem::create_directories(run.out_dir);
  std::filesystem::create_directories(run.work_dir);
  const std::filesystem::path store = Bake(run);
  std::unique_ptr<GlossyStore> g =
      Value(GlossyStore::Open(store, {.brdf = "phong:8", .eye = {}, .slices = {}, .threads = 1}));
  const RayCaster caster = Value(BuildBakedScene(g->info()));
  const int n = g->info().light_res, all_lights = 6 * n * n;
  std::vector<int> light_terms;
  for (int t : {16, 64, 256, 1024})
    if (t < all_lights) light_terms.push_back(t);
  light_terms.push_back(all_lights);
  const std::vector<int> brdf_terms = {16, 64, 256, 1024, 0};  // 0: every one
  Csv err(run.out_dir / "glossy_error.csv",
          "env,brdf,light_terms,brdf_terms,rel_rms_ref,rel_rms_all,rel_rms_dense,light_res,width");
  Csv time(run.out_dir / "glossy_time.csv", "brdf,light_terms,brdf_terms,seconds,light_res,width");
  std::vector<float> img(3 * g->samples().cells()), best(img.size());
  for (const char* env_name : {"grace", "pisa"}) {
    const EnvMap env =
        Value(LoadEnvMap(std::string(WB_SHARED_DATA) + "/probes/" + env_name + ".hdr"));
    const LightingCoefficients lighting = Value(LightingFromEnv(env, n, WaveletFilter::kHaar));
    const std::vector<float> cube = ResampleToCubemap(env, Cubemap(n));
    for (const char* brdf : {"phong:8", "phong:32", "phong:128"}) {
      charts::Check(g->SetBrdf(brdf));
      const std::vector<float> ref = Reference(*g, env, caster);
      const DenseTraceResult dense =
          Value(TraceDenseGlossy(caster, g->samples(), cube,
                                 {n, g->info().params.supersample, g->info().params.seed,
                                  caster.DefaultEpsilon(), g->pattern().per_texel},
                                 g->brdf(), g->views()));
      const double dense_err = CompareToReference(dense.rgb, ref).rel_rms;
      const BrdfSlices full = Value(g->Project(g->brdf(), {.terms = 0}));
      charts::Check(g->relighter().SetSlices(full));
      g->relighter().Relight(Value(SelectWaveletLights(lighting, all_lights)), best);
      for (int bt : brdf_terms) {
        charts::Check(g->relighter().SetSlices(CutSlices(full, bt)));
        for (int lt : light_terms) {
          const WaveletLights lights = Value(SelectWaveletLights(lighting, lt));
          double seconds = 1e30;
          for (int rep = 0; rep < (std::string(env_name) == "grace" ? 5 : 1); ++rep) {
            const double t0 = ThreadSeconds();
            g->relighter().Relight(lights, img);
            seconds = std::min(seconds, ThreadSeconds() - t0);
          }
          err.Row(env_name, brdf, lt, bt, CompareToReference(img, ref).rel_rms,
                  CompareToReference(img, best).rel_rms, dense_err, n, g->samples().width);
          if (std::string(env_name) == "grace")
            time.Row(brdf, lt, bt, seconds, n, g->samples().width);
        }
      }
      std::fprintf(stderr, "  %s %s: dense %.4f\n", env_name, brdf, dense_err);
    }
  }
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  wavebake::charts::program = "bench_charts_glossy";
  wavebake::RunConfig run;
  const char* usage = "usage: bench_charts_glossy OUT_DIR [--quick] [--threads T]";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      run.quick = true;
    } else if (arg == "--threads" && i + 1 < argc) {
      run.threads = std::atoi(argv[++i]);
    } else if (!arg.empty() && arg[0] != '-' && run.out_dir.empty()) {
      run.out_dir = arg;
    } else {
      wavebake::charts::Die(usage);
    }
  }
  if (run.out_dir.empty() || run.threads < 1) wavebake::charts::Die(usage);
  run.work_dir = std::filesystem::temp_directory_path() /
                 ("wavebake-charts-glossy-" + std::to_string(::getpid()));
  wavebake::Run(run);
  std::filesystem::remove_all(run.work_dir);
  return 0;
}
