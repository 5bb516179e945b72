#include "runtime/env/env_builtin.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "runtime/env/latlong.h"

namespace wavebake {

namespace {

constexpr double kDeg = std::numbers::pi / 180;

double Overlap(double a0, double a1, double b0, double b1) {
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}

// Pixel footprint in (φ, μ = cos θ), where solid angle is area.
struct Footprint {
  double phi0, phi1, mu0, mu1;  // mu0 < mu1
  double Area() const { return (phi1 - phi0) * (mu1 - mu0); }
};

// Mean of the sky gradient and the ground over the pixel: the gradient is
// linear in μ = sin(elevation), so its mean is at the mean μ of the part
// above the horizon.
Vec3 MeanSky(const SkyParams& p, const Footprint& f) {
  const double up = Overlap(f.mu0, f.mu1, 0, 1), down = Overlap(f.mu0, f.mu1, -1, 0);
  const double mean_mu = up > 0 ? 0.5 * (std::max(f.mu0, 0.0) + f.mu1) : 0;
  const Vec3 sky = p.horizon + (p.zenith - p.horizon) * static_cast<float>(mean_mu);
  return (sky * static_cast<float>(up) + p.ground * static_cast<float>(down)) /
         static_cast<float>(up + down);
}

// Fraction of the pixel inside the area light (a rectangle in φ and μ too).
double AreaLightCover(const SkyParams& p, const Footprint& f) {
  const double phi = Overlap(f.phi0, f.phi1, p.area_azimuth_min * kDeg, p.area_azimuth_max * kDeg);
  const double mu = Overlap(f.mu0, f.mu1, std::sin(p.area_elevation_min * kDeg),
                            std::sin(p.area_elevation_max * kDeg));
  return phi * mu / f.Area();
}

// Fraction of the pixel inside the sun's disk: 16 × 16 cells of equal area
// (uniform in φ and μ), only near the sun.
double SunCover(const SkyParams& p, const Footprint& f, Vec3 sun_dir) {
  constexpr int kCells = 16;
  const double cos_radius = std::cos(p.sun_radius * kDeg);
  const double mid_mu = 0.5 * (f.mu0 + f.mu1), mid_phi = 0.5 * (f.phi0 + f.phi1);
  const Vec3 centre = LatLongToDirection(
      {0.5 + mid_phi / (2 * std::numbers::pi), std::acos(mid_mu) / std::numbers::pi});
  // Pixels are far smaller than a radian: skip those clearly apart.
  if (std::acos(std::min(1.0f, Dot(centre, sun_dir))) > p.sun_radius * kDeg + 0.1) return 0;
  int inside = 0;
  for (int j = 0; j < kCells; ++j) {
    const double mu = f.mu0 + (j + 0.5) / kCells * (f.mu1 - f.mu0);
    for (int i = 0; i < kCells; ++i) {
      const double phi = f.phi0 + (i + 0.5) / kCells * (f.phi1 - f.phi0);
      const Vec3 d = LatLongToDirection(
          {0.5 + phi / (2 * std::numbers::pi), std::acos(mu) / std::numbers::pi});
      inside += Dot(d, sun_dir) >= cos_radius;
    }
  }
  return double(inside) / (kCells * kCells);
}

}  // namespace

EnvMap MakeConstantEnv() {
  constexpr int kWidth = 16, kHeight = 8;
  return {kWidth, kHeight, std::vector<float>(kWidth * kHeight * 3, 1.0f)};
}

EnvMap MakeSkyEnv(const SkyParams& p) {
  const Vec3 sun_dir = LatLongToDirection({0.5 + p.sun_azimuth / 360, 0.5 - p.sun_elevation / 180});
  EnvMap env{p.width, p.width / 2, {}};
  env.rgb.resize(size_t(env.width) * env.height * 3);
  for (int y = 0; y < env.height; ++y) {
    for (int x = 0; x < env.width; ++x) {
      const Footprint f{std::numbers::pi * (2.0 * x / env.width - 1),
                        std::numbers::pi * (2.0 * (x + 1) / env.width - 1),
                        std::cos(std::numbers::pi * (y + 1) / env.height),
                        std::cos(std::numbers::pi * y / env.height)};
      const Vec3 l = MeanSky(p, f) + p.area_light * static_cast<float>(AreaLightCover(p, f)) +
                     p.sun * static_cast<float>(SunCover(p, f, sun_dir));
      float* o = &env.rgb[(size_t(y) * env.width + x) * 3];
      o[0] = l.x, o[1] = l.y, o[2] = l.z;
    }
  }
  return env;
}

}  // namespace wavebake
