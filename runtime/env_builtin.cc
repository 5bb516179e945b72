#include "runtime/env_builtin.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "runtime/latlong.h"

namespace wavebake {

namespace {

constexpr double kDeg = std::numbers::pi / 180;

Vec3 SkyRadiance(const SkyParams& p, Vec3 d, Vec3 sun_dir) {
  Vec3 l = d.y >= 0 ? p.horizon + (p.zenith - p.horizon) * d.y : p.ground;
  if (Dot(d, sun_dir) >= std::cos(p.sun_radius * kDeg)) l = l + p.sun;
  const double elevation = std::asin(std::clamp(d.y, -1.0f, 1.0f)) / kDeg;
  const double azimuth = std::atan2(d.x, -d.z) / kDeg;  // the lat-long φ
  if (elevation >= p.area_elevation_min && elevation < p.area_elevation_max &&
      azimuth >= p.area_azimuth_min && azimuth < p.area_azimuth_max) {
    l = l + p.area_light;
  }
  return l;
}

}  // namespace

EnvMap MakeConstantEnv() {
  constexpr int kWidth = 16, kHeight = 8;
  return {kWidth, kHeight, std::vector<float>(kWidth * kHeight * 3, 1.0f)};
}

EnvMap MakeSkyEnv(const SkyParams& p) {
  constexpr int kSub = 4;
  const Vec3 sun_dir = LatLongToDirection(
      {0.5 + p.sun_azimuth / 360, 0.5 - p.sun_elevation / 180});
  EnvMap env{p.width, p.width / 2, std::vector<float>(size_t(p.width) * (p.width / 2) * 3)};
  for (int y = 0; y < env.height; ++y) {
    for (int x = 0; x < env.width; ++x) {
      Vec3 sum;
      double weight = 0;
      for (int j = 0; j < kSub; ++j) {
        const double v = (y + (j + 0.5) / kSub) / env.height;
        const float w = static_cast<float>(std::sin(std::numbers::pi * v));
        for (int i = 0; i < kSub; ++i) {
          const double u = (x + (i + 0.5) / kSub) / env.width;
          sum = sum + SkyRadiance(p, LatLongToDirection({u, v}), sun_dir) * w;
          weight += w;
        }
      }
      const Vec3 l = sum / static_cast<float>(weight);
      float* o = &env.rgb[(size_t(y) * env.width + x) * 3];
      o[0] = l.x, o[1] = l.y, o[2] = l.z;
    }
  }
  return env;
}

}  // namespace wavebake
