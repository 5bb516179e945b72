#include "runtime/env/env_map.h"

#include <algorithm>
#include <cmath>

#include "runtime/env/latlong.h"

namespace wavebake {

namespace {
int Wrap(int x, int n) { return ((x % n) + n) % n; }
}  // namespace

Vec3 EnvRadiance(const EnvMap& env, Vec3 d) {
  const LatLong p = DirectionToLatLong(d);
  const int x = Wrap(static_cast<int>(std::floor(p.u * env.width)), env.width);
  const int y = std::clamp(static_cast<int>(std::floor(p.v * env.height)), 0, env.height - 1);
  return env.Pixel(x, y);
}

EnvMap Rotated(const EnvMap& env, double degrees) {
  // R_y(α) d(φ) = d(φ − α) (latlong.h), so the rotated map at azimuth φ shows
  // the original at φ + α: output column x reads input column x + shift.
  if (!std::isfinite(degrees)) return env;  // callers validate user input
  double turns = std::fmod(degrees / 360.0, 1.0);
  if (turns < 0) turns += 1;
  const double shift = turns * env.width;
  const int whole = static_cast<int>(std::floor(shift));
  const float frac = static_cast<float>(shift - whole);
  EnvMap out{env.width, env.height, std::vector<float>(env.rgb.size())};
  for (int y = 0; y < env.height; ++y) {
    for (int x = 0; x < env.width; ++x) {
      const Vec3 a = env.Pixel(Wrap(x + whole, env.width), y);
      const Vec3 b = env.Pixel(Wrap(x + whole + 1, env.width), y);
      const Vec3 v = frac == 0 ? a : a * (1 - frac) + b * frac;
      float* o = &out.rgb[(static_cast<size_t>(y) * env.width + x) * 3];
      o[0] = v.x, o[1] = v.y, o[2] = v.z;
    }
  }
  return out;
}

}  // namespace wavebake
