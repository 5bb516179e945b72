#pragma once
// One whole bake through the product path (driver/bake/embedded_bake.h: the
// coordinator and worker loops in this process), timed phase by phase in
// wall and CPU seconds (the process's user + system time, all threads):
// what bench_bake_phases prints and bench_refine_bake compares. Header-only:
// every bench/*.cc is its own binary.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "driver/bake/embedded_bake.h"
#include "driver/jobs/job_query.h"
#include "worker/columns/store_manifest.h"

namespace wavebake::bench {

inline double ProcessCpuSeconds() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec +
         1e-6 * u.ru_stime.tv_usec;
}

inline double PeakRssMiB() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // Linux: kilobytes
}

struct PhaseTime {
  double wall = 0, cpu = 0;
};

struct PhasedBake {
  int64_t rays = 0;
  int tiles = 0, groups = 0;
  uint64_t store_bytes = 0;
  PhaseTime total, setup, baking, transforming, finalizing;
  nlohmann::json ToJson() const {
    auto phase = [](const PhaseTime& p) {
      return nlohmann::json{{"wall_s", p.wall}, {"cpu_s", p.cpu}};
    };
    return {{"rays", rays},
            {"tiles", tiles},
            {"groups", groups},
            {"store_bytes", store_bytes},
            {"wall_s", total.wall},
            {"cpu_s", total.cpu},
            {"setup", phase(setup)},
            {"baking", phase(baking)},
            {"transforming", phase(transforming)},
            {"finalizing", phase(finalizing)}};
  }
};

// Repeated bakes of one job (non-empty) as one: every time, wall and CPU of
// each phase, is the median of its runs, taken on its own (the medians of
// two phases may come from different runs); the counts are the last run's.
inline PhasedBake MedianBake(std::span<const PhasedBake> runs) {
  auto median = [&](auto field) {
    std::vector<double> v;
    for (const PhasedBake& r : runs) v.push_back(field(r));
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  PhasedBake m = runs.back();
  for (PhaseTime PhasedBake::*phase : {&PhasedBake::total, &PhasedBake::setup, &PhasedBake::baking,
                                       &PhasedBake::transforming, &PhasedBake::finalizing}) {
    (m.*phase).wall = median([&](const PhasedBake& r) { return (r.*phase).wall; });
    (m.*phase).cpu = median([&](const PhasedBake& r) { return (r.*phase).cpu; });
  }
  return m;
}

// `on_phase(name, wall seconds so far)` at each phase change (may be empty).
inline absl::StatusOr<PhasedBake> RunPhasedBake(
    const std::string& scene, const BakeParams& params, const std::filesystem::path& store,
    int workers, const std::function<void(const std::string&, double)>& on_phase = {}) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const double cpu0 = ProcessCpuSeconds();
  auto now = [&] {
    return PhaseTime{std::chrono::duration<double>(Clock::now() - t0).count(),
                     ProcessCpuSeconds() - cpu0};
  };
  std::map<v1::Phase, PhaseTime> started;  // first event of each phase
  v1::Phase last = v1::PHASE_UNSPECIFIED;
  auto on_event = [&](const v1::JobEvent& e) {
    if (e.phase() == last) return;
    last = e.phase();
    const PhaseTime at = now();
    started.emplace(e.phase(), at);
    if (on_phase) on_phase(v1::Phase_Name(e.phase()), at.wall);
  };
  absl::StatusOr<v1::Job> job =
      driver::EmbeddedBake(scene, params, store, {.workers = workers, .on_event = on_event});
  if (!job.ok()) return job.status();
  if (job->phase() != v1::PHASE_DONE) return absl::InternalError(driver::JobOutcome(*job));
  PhasedBake r;
  r.total = now();
  auto span = [&](v1::Phase from, v1::Phase to) {
    const PhaseTime a = started.count(from) ? started[from] : PhaseTime{};
    const PhaseTime b = started.count(to) ? started[to] : r.total;
    return PhaseTime{b.wall - a.wall, b.cpu - a.cpu};
  };
  r.rays = job->rays_traced();
  r.tiles = job->tiles();
  r.groups = job->groups();
  r.store_bytes = DirectoryBytes(store);
  r.setup = span(v1::PHASE_UNSPECIFIED, v1::PHASE_BAKING);
  r.baking = span(v1::PHASE_BAKING, v1::PHASE_TRANSFORMING);
  r.transforming = span(v1::PHASE_TRANSFORMING, v1::PHASE_FINALIZING);
  r.finalizing = span(v1::PHASE_FINALIZING, v1::PHASE_DONE);
  return r;
}

}  // namespace wavebake::bench
