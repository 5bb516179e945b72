#include "runtime/env/env_cross.h"

#include <algorithm>
#include <cmath>

#include "core/directions/cubemap.h"
#include "runtime/env/sphere_overlap.h"

namespace wavebake {

namespace {

// Where a face sits in the cross (in face units) and the face-local (s, t)
// of direction d, inverting the table in env_cross.h.
struct CrossSpot {
  int col, row;
  double s, t;
};

CrossSpot Locate(Vec3 d) {
  const double ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  if (ax >= ay && ax >= az) {
    return d.x > 0 ? CrossSpot{2, 1, d.z / ax, -d.y / ax} : CrossSpot{0, 1, -d.z / ax, -d.y / ax};
  }
  if (ay >= az) {
    return d.y > 0 ? CrossSpot{1, 0, d.x / ay, -d.z / ay} : CrossSpot{1, 2, d.x / ay, d.z / ay};
  }
  return d.z < 0 ? CrossSpot{1, 1, d.x / az, -d.y / az} : CrossSpot{1, 3, d.x / az, d.y / az};
}

}  // namespace

EnvMap VerticalCrossToLatLong(const EnvMap& cross) {
  const int a = cross.width / 3;
  const Cubemap faces(a);
  // Texel centres fall on cross pixel centres, never on an edge.
  std::vector<float> texels(3 * size_t(faces.size()));
  for (int m = 0; m < faces.size(); ++m) {
    const CrossSpot c = Locate(faces.TexelCenter(m));
    const int i = std::clamp(static_cast<int>(0.5 * (c.s + 1) * a), 0, a - 1);
    const int j = std::clamp(static_cast<int>(0.5 * (c.t + 1) * a), 0, a - 1);
    const Vec3 l = cross.Pixel(c.col * a + i, c.row * a + j);
    texels[3 * m] = l.x, texels[3 * m + 1] = l.y, texels[3 * m + 2] = l.z;
  }
  return {4 * a, 2 * a, SphereOverlap(4 * a, 2 * a, faces).LatLongFromCube(texels)};
}

}  // namespace wavebake
