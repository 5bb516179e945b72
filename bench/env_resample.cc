// Environment → light cubemap: exact area averaging (ResampleToCubemap)
// beside naive centre point sampling, on grace.hdr (tiny, very bright
// sources) at N = 32 and 128. Prints the time ratio and each method's error
// in ∫ L dω (Σ_m L_m Ω_m against SphereIntegral) after the table.
#include "runtime/env/env_resample.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "core/directions/cubemap.h"
#include "runtime/env/env_map.h"
#include "runtime/env/sphere_overlap.h"

namespace wavebake {
namespace {

const EnvMap& Grace() {
  static const EnvMap env = [] {
    absl::StatusOr<EnvMap> e = LoadEnvMap(std::string(WB_SHARED_DATA) + "/probes/grace.hdr");
    if (!e.ok()) {
      std::fprintf(stderr, "%s\n", std::string(e.status().message()).c_str());
      std::exit(1);
    }
    return *std::move(e);
  }();
  return env;
}

// Largest relative error of Σ_m L_m Ω_m over the three channels.
double EnergyError(const std::vector<float>& l, const Cubemap& cube) {
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    double sum = 0;
    for (int m = 0; m < cube.size(); ++m) sum += l[3 * m + c] * cube.SolidAngle(m);
    worst = std::max(worst, std::fabs(sum / SphereIntegral(Grace(), c) - 1));
  }
  return worst;
}

void BM_AreaAverage(benchmark::State& state) {
  const Cubemap cube(static_cast<int>(state.range(0)));
  std::vector<float> l;
  for (auto _ : state) benchmark::DoNotOptimize(l = ResampleToCubemap(Grace(), cube));
  state.counters["energy_err"] = EnergyError(l, cube);
}

// The per-frame cost once the overlaps are built (a rotating environment).
void BM_AreaAverageReused(benchmark::State& state) {
  const Cubemap cube(static_cast<int>(state.range(0)));
  const SphereOverlap overlap(Grace().width, Grace().height, cube);
  std::vector<float> l;
  for (auto _ : state) benchmark::DoNotOptimize(l = overlap.CubeFromLatLong(Grace().rgb));
  state.counters["energy_err"] = EnergyError(l, cube);
}

void BM_PointSample(benchmark::State& state) {
  const Cubemap cube(static_cast<int>(state.range(0)));
  std::vector<float> l;
  for (auto _ : state) benchmark::DoNotOptimize(l = PointSampleToCubemap(Grace(), cube));
  state.counters["energy_err"] = EnergyError(l, cube);
}

BENCHMARK(BM_AreaAverage)->Arg(32)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AreaAverageReused)->Arg(32)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PointSample)->Arg(32)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

// Console output plus a record of each run's time, for the ratios.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) seconds_[r.benchmark_name()] = r.GetAdjustedRealTime();
    ConsoleReporter::ReportRuns(runs);
  }
  void PrintRatios() const {
    for (const char* n : {"32", "128"}) {
      const std::string point = std::string("BM_PointSample/") + n + "/real_time";
      for (const char* area : {"BM_AreaAverage/", "BM_AreaAverageReused/"}) {
        const std::string name = std::string(area) + n + "/real_time";
        if (seconds_.count(name) && seconds_.count(point)) {
          std::printf("N=%-4s %-22s / point sampling: %.1fx the time\n", n, area,
                      seconds_.at(name) / seconds_.at(point));
        }
      }
    }
  }

 private:
  std::map<std::string, double> seconds_;
};

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  wavebake::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.PrintRatios();
  benchmark::Shutdown();
  return 0;
}
