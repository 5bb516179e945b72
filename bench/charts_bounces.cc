// Chart 12 of docs/RESULTS.md (diffuse interreflection, core/bake/bake_gather.h):
// per case and B = 0..4, a whole bake through the product path (timed), its
// relighting under grace.hdr against one path-traced reference with
// kReferenceBounces bounces (runtime/reference/path_reference.h, which shares
// no code with the gather), and the energy of each bounce from the B = 4
// store's .zattrs record. Cases: cubes-wall on a camera layout (its bounces
// gather from the meshes' vertices) and the bunny on hilbert:64x64.
//
//   build/bench_charts_bounces OUT_DIR [--quick] [--threads T]
//
// Writes OUT_DIR/bounces.csv (case,bounces,bake_wall_s,bake_cpu_s,rel_rms,
// reference_rel_se) and OUT_DIR/bounce_energy.csv (case,bounce,rms_ratio).
// --quick: N = 8, camera:32x32, a looser reference, for a smoke run.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/bake_run.h"
#include "bench/chart_util.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/eval.h"
#include "runtime/reference/path_reference.h"
#include "runtime/relight/store_relight.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake {
namespace {

using charts::Check;
using charts::Csv;
using charts::Die;
using charts::Value;

constexpr int kMaxChartBounces = 4;
constexpr int kReferenceBounces = 8;  // the light of (nearly) every bounce
constexpr int kTerms = 256;           // wavelet lights of the relighting

struct BounceCase {
  std::string name, scene, layout;
};

void RunCase(const BounceCase& c, const std::filesystem::path& out, bool quick, int threads,
             const EnvMap& env, Csv& csv, Csv& energy) {
  const std::filesystem::path work = out / "work";
  std::filesystem::create_directories(work);
  std::optional<ReferenceResult> reference;
  for (int b = 0; b <= kMaxChartBounces; ++b) {
    BakeParams p;
    p.light_res = quick ? 8 : 16;
    p.layout = c.layout;
    p.bounces = b;
    const std::filesystem::path store = work / (c.name + "_b" + std::to_string(b) + ".wbk");
    std::filesystem::remove_all(store);
    const bench::PhasedBake bake = Value(bench::RunPhasedBake(c.scene, p, store, threads));
    OpenedStore opened = Value(OpenStore(store));
    if (!reference) {  // the samples are the same for every B
      const Scene scene = Value(LoadScene(c.scene));
      reference = Value(ComputePathReference(scene, opened.samples, env,
                                             {.bounces = kReferenceBounces,
                                              .target_rel_se = quick ? 0.02 : 0.004,
                                              .threads = threads,
                                              .min_paths = quick ? 128 : 1024}));
    }
    const std::vector<float> image = Value(RelightImage(opened, env, kTerms));
    const ErrorStats e = Value(CompareFinite(image, reference->rgb, "the relighting"));
    std::printf("%-10s B=%d  bake %7.2f s wall %7.2f s cpu  rel_rms %.5f (reference rel_se %.5f)\n",
                c.name.c_str(), b, bake.total.wall, bake.total.cpu, e.rel_rms, reference->rel_se);
    std::fflush(stdout);
    csv.Row(c.name, b, bake.total.wall, bake.total.cpu, e.rel_rms, reference->rel_se);
    if (b == kMaxChartBounces) {
      const nlohmann::json& ratio = opened.info.attrs.at("bounces").at("rms_ratio");
      for (size_t k = 0; k < ratio.size(); ++k) energy.Row(c.name, k, ratio[k].get<double>());
    }
    std::filesystem::remove_all(store);
  }
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  using namespace wavebake;
  charts::program = "bench_charts_bounces";
  if (argc < 2) Die("usage: bench_charts_bounces OUT_DIR [--quick] [--threads T]");
  const std::filesystem::path out = argv[1];
  bool quick = false;
  int threads = 2;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--threads" && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else {
      Die("unknown argument " + a);
    }
  }
  std::filesystem::create_directories(out);
  const std::string data = WB_SHARED_DATA;
  const EnvMap env = Value(LoadEnvMap(data + "/probes/grace.hdr"));
  const std::vector<BounceCase> cases = {
      {"cubes-wall", "builtin:cubes-wall", quick ? "camera:32x32" : "camera:64x64"},
      {"bunny", data + "/models/bunny.obj", "hilbert:64x64"}};
  Csv csv(out / "bounces.csv", "case,bounces,bake_wall_s,bake_cpu_s,rel_rms,reference_rel_se");
  Csv energy(out / "bounce_energy.csv", "case,bounce,rms_ratio");
  for (const BounceCase& c : cases) RunCase(c, out, quick, threads, env, csv, energy);
  std::filesystem::remove_all(out / "work");
  return 0;
}
