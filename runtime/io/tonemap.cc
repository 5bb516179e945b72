#include "runtime/io/tonemap.h"

#include <cmath>

namespace wavebake {

uint8_t EncodeSrgb8(float linear) {
  const double c = linear > 0 ? (linear < 1 ? linear : 1.0) : 0.0;  // NaN fails both: 0
  const double e = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(e * 255));
}

std::array<uint8_t, 3> ToneMapPixel(Vec3 linear, float scale, Vec3 background) {
  const bool masked = std::isnan(linear.x) || std::isnan(linear.y) || std::isnan(linear.z);
  const Vec3 c = masked ? background : linear * scale;
  return {EncodeSrgb8(c.x), EncodeSrgb8(c.y), EncodeSrgb8(c.z)};
}

}  // namespace wavebake
