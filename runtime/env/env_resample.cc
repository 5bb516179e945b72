#include "runtime/env/env_resample.h"

#include "runtime/env/latlong.h"
#include "runtime/env/sphere_overlap.h"

namespace wavebake {

std::vector<float> ResampleToCubemap(const EnvMap& env, const Cubemap& cube) {
  return SphereOverlap(env.width, env.height, cube).CubeFromLatLong(env.rgb);
}

std::vector<float> PointSampleToCubemap(const EnvMap& env, const Cubemap& cube) {
  std::vector<float> out(3 * static_cast<size_t>(cube.size()));
  for (int m = 0; m < cube.size(); ++m) {
    const Vec3 l = EnvRadiance(env, cube.TexelCenter(m));
    out[3 * m] = l.x, out[3 * m + 1] = l.y, out[3 * m + 2] = l.z;
  }
  return out;
}

double SphereIntegral(const EnvMap& env, int channel) {
  double total = 0;
  for (int y = 0; y < env.height; ++y) {
    double row = 0;
    for (int x = 0; x < env.width; ++x) row += env.Pixel(x, y)[channel];
    total += row * LatLongPixelSolidAngle(y, env.width, env.height);
  }
  return total;
}

}  // namespace wavebake
