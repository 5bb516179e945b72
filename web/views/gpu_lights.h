#pragma once
// The lighting of a GPU frame (web/views/gpu_view.h, the job page's GPU path in
// web/views/routes_gpu.cc): a catalogue probe, turned about +Y, projected on the
// store's cube (Haar rows) and cut to its n area-weighted wavelet lights —
// SelectWaveletLights, the same terms the CPU relighter and the relight
// view's server frames use. Probes and their projectors stay cached (a
// probe is a catalogue name, never a path).
#include <map>
#include <mutex>
#include <span>
#include <string>

#include "absl/status/statusor.h"
#include "runtime/env/env_map.h"
#include "runtime/relight/lighting.h"
#include "web/views/probe_catalogue.h"

namespace wavebake::web {

class GpuLights {
 public:
  explicit GpuLights(ProbeCatalogue probes) : probes_(std::move(probes)) {}
  const ProbeCatalogue& probes() const { return probes_; }
  // Errors name terms (< 1), rotate (not finite) or probe (not listed).
  // support: SupportSolidAngles(light_res).
  absl::StatusOr<WaveletLights> Lights(const std::string& probe, double rotate, int terms,
                                       int light_res, std::span<const float> support);

 private:
  struct Probe {
    EnvMap env;
    std::map<int, EnvProjector> projectors;  // by light_res
  };
  ProbeCatalogue probes_;
  std::mutex mu_;
  std::map<std::string, Probe> cache_;  // never evicted: entries stay put
};

}  // namespace wavebake::web
