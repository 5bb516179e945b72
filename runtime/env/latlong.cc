#include "runtime/env/latlong.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wavebake {

Vec3 LatLongToDirection(LatLong p) {
  const double theta = std::numbers::pi * p.v;
  const double phi = std::numbers::pi * (2 * p.u - 1);
  const double st = std::sin(theta);
  return {static_cast<float>(st * std::sin(phi)), static_cast<float>(std::cos(theta)),
          static_cast<float>(-st * std::cos(phi))};
}

LatLong DirectionToLatLong(Vec3 d) {
  const double len = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
  if (len == 0) return {0.5, 0};
  const double cos_theta = std::clamp(d.y / len, -1.0, 1.0);
  // atan2 ∈ [−π, π] so u ∈ [0, 1]; u = 1 (φ = π) is the same column as u = 0.
  const double u = 0.5 * (1 + std::atan2(double(d.x), -double(d.z)) / std::numbers::pi);
  return {u, std::acos(cos_theta) / std::numbers::pi};
}

double LatLongPixelSolidAngle(int y, int width, int height) {
  const double t0 = std::numbers::pi * y / height, t1 = std::numbers::pi * (y + 1) / height;
  return 2 * std::numbers::pi * (std::cos(t0) - std::cos(t1)) / width;
}

}  // namespace wavebake
