#include "web/views/gpu_lights.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace wavebake::web {

absl::StatusOr<WaveletLights> GpuLights::Lights(const std::string& name, double rotate, int terms,
                                                int light_res, std::span<const float> support) {
  if (terms < 1) return absl::InvalidArgumentError(absl::StrCat("terms: ", terms, " < 1"));
  if (!std::isfinite(rotate))
    return absl::InvalidArgumentError("rotate: not a finite number of degrees");
  EnvProjector* projector = nullptr;
  const EnvMap* env = nullptr;
  {
    std::lock_guard lock(mu_);
    auto it = cache_.find(name);
    if (it == cache_.end()) {
      absl::StatusOr<std::string> spec = probes_.Spec(name);
      if (!spec.ok()) return spec.status();
      absl::StatusOr<EnvMap> loaded = LoadEnvMap(*spec);
      if (!loaded.ok()) return loaded.status();
      it = cache_.emplace(name, Probe{*std::move(loaded), {}}).first;
    }
    Probe& p = it->second;
    env = &p.env;
    auto pj = p.projectors.find(light_res);
    if (pj == p.projectors.end()) {
      absl::StatusOr<EnvProjector> created =
          EnvProjector::Create(p.env.width, p.env.height, light_res, WaveletFilter::kHaar);
      if (!created.ok()) return created.status();
      pj = p.projectors.emplace(light_res, *std::move(created)).first;
    }
    projector = &pj->second;
  }
  absl::StatusOr<LightingCoefficients> lighting =
      rotate != 0 ? projector->Project(Rotated(*env, rotate)) : projector->Project(*env);
  if (!lighting.ok()) return lighting.status();
  return SelectWaveletLights(*lighting, terms, support);
}

}  // namespace wavebake::web
