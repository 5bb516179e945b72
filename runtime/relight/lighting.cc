#include "runtime/relight/lighting.h"

#include <cmath>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/columns/nla.h"
#include "core/directions/cubemap.h"
#include "runtime/env/env_map.h"
#include "runtime/relight/row_basis.h"

namespace wavebake {

LightingCoefficients ProjectLighting(std::span<const float> cube_rgb, int light_res,
                                     WaveletFilter row_filter) {
  LightingCoefficients out;
  out.light_res = light_res;
  out.row_filter = row_filter;
  out.rgb.assign(cube_rgb.begin(), cube_rgb.end());
  RowTransformCube(row_filter, light_res, out.rgb);
  return out;
}

absl::StatusOr<EnvProjector> EnvProjector::Create(int env_width, int env_height, int light_res,
                                                  WaveletFilter row_filter) {
  if (light_res < 1 || light_res > 256 || (light_res & (light_res - 1)) != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("light_res: ", light_res, " is not a power of two in [1, 256]"));
  }
  if (env_height <= 0 || env_width != 2 * env_height) {
    return absl::InvalidArgumentError(absl::StrCat("env: ", env_width, "x", env_height,
                                                   " is not a lat-long map (width = 2 height)"));
  }
  return EnvProjector(SphereOverlap(env_width, env_height, Cubemap(light_res)), env_width,
                      env_height, light_res, row_filter);
}

absl::StatusOr<LightingCoefficients> EnvProjector::Project(const EnvMap& env) const {
  if (env.width != width_ || env.height != height_ ||
      env.rgb.size() != static_cast<size_t>(env.width) * env.height * 3) {
    return absl::InvalidArgumentError(absl::StrCat("env: ", env.width, "x", env.height,
                                                   " is not the ", width_, "x", height_,
                                                   " map this projector was built for"));
  }
  return ProjectLighting(overlap_.CubeFromLatLong(env.rgb), light_res_, row_filter_);
}

absl::StatusOr<LightingCoefficients> LightingFromEnv(const EnvMap& env, int light_res,
                                                     WaveletFilter row_filter) {
  absl::StatusOr<EnvProjector> projector =
      EnvProjector::Create(env.width, env.height, light_res, row_filter);
  if (!projector.ok()) return projector.status();
  return projector->Project(env);
}

std::vector<float> LightImportance(const LightingCoefficients& lighting,
                                   std::span<const float> support) {
  std::vector<float> own;
  if (support.empty()) {
    own = SupportSolidAngles(lighting.light_res);
    support = own;
  }
  std::vector<float> importance(lighting.size());
  for (int m = 0; m < lighting.size(); ++m) {
    const float* c = &lighting.rgb[3 * static_cast<size_t>(m)];
    const double norm = std::sqrt(double{c[0]} * c[0] + double{c[1]} * c[1] + double{c[2]} * c[2]);
    importance[m] = static_cast<float>(norm * support[m]);
  }
  return importance;
}

absl::StatusOr<WaveletLights> SelectWaveletLights(const LightingCoefficients& lighting, int terms,
                                                  std::span<const float> support) {
  if (terms <= 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("terms: ", terms, " wavelet lights requested; need at least 1"));
  }
  const std::vector<float> importance = LightImportance(lighting, support);
  WaveletLights out;
  out.light_res = lighting.light_res;
  for (uint32_t m : TopK(importance, {}, terms)) {
    if (importance[m] == 0) break;  // TopK is sorted: only zeros follow
    const float* c = &lighting.rgb[3 * static_cast<size_t>(m)];
    out.lights.push_back({m, {c[0], c[1], c[2]}});
  }
  return out;
}

WaveletLights AllWaveletLights(const LightingCoefficients& lighting) {
  WaveletLights out;
  out.light_res = lighting.light_res;
  out.lights.reserve(lighting.size());
  for (int m = 0; m < lighting.size(); ++m) {
    const float* c = &lighting.rgb[3 * static_cast<size_t>(m)];
    out.lights.push_back({static_cast<uint32_t>(m), {c[0], c[1], c[2]}});
  }
  return out;
}

}  // namespace wavebake
