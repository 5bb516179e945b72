// What diffuse bounces cost (core/transport/bounce_gather.h, applied by
// TRANSFORM_COLUMNS): whole bakes through the product path at B = 0..4, and
// the time each bounce adds against the direct bake's.
//
//   build/bench_bounce_cost WORK_DIR [--quick] [--workers W] [--max-bounces B] [--case NAME]
//
// Cases: the bunny and spot on hilbert:64x64 (../shared/data) and cubes-wall
// on camera:128x128, N = 32 (--quick: spot only, N = 16; --case: that one
// only). Per case and B: wall and CPU seconds of the bake, and of its
// transforming phase (where the bounces run), and
//   per_bounce = (cpu(B) − cpu(0)) / B / cpu(0),
// the ratio the goal "each bounce costs ≤ 1.0× the direct bake" is about.
// The last line is one JSON object with every number.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bake_run.h"

namespace wavebake {
namespace {

[[noreturn]] void Die(const std::string& what) {
  std::fprintf(stderr, "bench_bounce_cost: %s\n", what.c_str());
  std::exit(1);
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  using namespace wavebake;
  if (argc < 2)
    Die("usage: bench_bounce_cost WORK_DIR [--quick] [--workers W] [--max-bounces B] [--case "
        "NAME]");
  const std::filesystem::path work = argv[1];
  bool quick = false;
  int workers = 2, max_bounces = 4;
  std::string only;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--workers" && i + 1 < argc) {
      workers = std::atoi(argv[++i]);
    } else if (a == "--max-bounces" && i + 1 < argc) {
      max_bounces = std::atoi(argv[++i]);
    } else if (a == "--case" && i + 1 < argc) {
      only = argv[++i];
    } else {
      Die("unknown argument " + a);
    }
  }
  std::filesystem::create_directories(work);
  const std::string models = std::string(WB_SHARED_DATA) + "/models/";
  struct Case {
    std::string name, scene, layout;
  };
  std::vector<Case> cases = {{"spot", models + "spot.obj", "hilbert:64x64"}};
  if (!quick) {
    cases.insert(cases.begin(), {"bunny", models + "bunny.obj", "hilbert:64x64"});
    // A camera's bounces add the auxiliary vertex set's rows (core/bake/bake_gather.h).
    cases.push_back({"cubes-wall", "builtin:cubes-wall", "camera:128x128"});
  }
  if (!only.empty()) {
    std::erase_if(cases, [&](const Case& c) { return c.name != only; });
    if (cases.empty()) Die("--case: no case named " + only);
  }

  nlohmann::json all = nlohmann::json::array();
  for (const auto& [name, scene, layout] : cases) {
    double cpu0 = 0;
    for (int b = 0; b <= max_bounces; ++b) {
      BakeParams p;
      p.light_res = quick ? 16 : 32;
      p.layout = layout;
      p.bounces = b;
      const std::filesystem::path out = work / (name + "_b" + std::to_string(b) + ".wbk");
      std::filesystem::remove_all(out);
      absl::StatusOr<bench::PhasedBake> r = bench::RunPhasedBake(scene, p, out, workers);
      if (!r.ok()) Die(r.status().ToString());
      if (b == 0) cpu0 = r->total.cpu;
      const double per_bounce = b > 0 && cpu0 > 0 ? (r->total.cpu - cpu0) / b / cpu0 : 0.0;
      std::printf(
          "%-10s B=%d  wall %7.2f s  cpu %7.2f s  transforming cpu %7.2f s  per bounce %.3fx\n",
          name.c_str(), b, r->total.wall, r->total.cpu, r->transforming.cpu, per_bounce);
      std::fflush(stdout);
      nlohmann::json j = r->ToJson();
      j["case"] = name;
      j["bounces"] = b;
      j["per_bounce_cpu_ratio"] = per_bounce;
      all.push_back(j);
      std::filesystem::remove_all(out);
    }
  }
  std::printf("%s\n", all.dump().c_str());
  return 0;
}
