#include "runtime/near_field/light_canvas.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

struct CanvasFrame {
  double cs, sn;  // the light's u axis in (s, t)
};

// Radiance at in-plane (s, t): 0 off the rectangle, else radiance × texel.
Vec3 Radiance(const AreaLight& l, const CanvasFrame& f, double s, double t) {
  const double ds = s - l.centre[0], dt = t - l.centre[1];
  const double u = (ds * f.cs + dt * f.sn) / l.size[0] + 0.5;
  const double v = (-ds * f.sn + dt * f.cs) / l.size[1] + 0.5;
  if (!(u >= 0 && u < 1 && v >= 0 && v < 1)) return {0, 0, 0};
  if (l.texture.width == 0) return l.radiance;
  const int x = std::min(static_cast<int>(u * l.texture.width), l.texture.width - 1);
  const int y = std::min(static_cast<int>(v * l.texture.height), l.texture.height - 1);
  const Vec3 p = l.texture.Pixel(x, y);
  return {p.x * l.radiance.x, p.y * l.radiance.y, p.z * l.radiance.z};
}

}  // namespace

AffineMap2d LightCanvas::MapAt(double ps, double pt, double z, double face_size) const {
  const double span = z * face_size;  // the face's footprint on the plane
  return {span / extent_s, (ps - span / 2 - s0) / extent_s, span / extent_t,
          (pt - span / 2 - t0) / extent_t};
}

LightCanvas DrawLight(const AreaLight& light, int supersample) {
  const double a = light.rotation_degrees * std::numbers::pi / 180;
  const CanvasFrame f{std::cos(a), std::sin(a)};
  // The rotated rectangle's bounding box.
  const double hs = 0.5 * (std::fabs(f.cs) * light.size[0] + std::fabs(f.sn) * light.size[1]);
  const double ht = 0.5 * (std::fabs(f.sn) * light.size[0] + std::fabs(f.cs) * light.size[1]);
  LightCanvas c;
  c.res = light.resolution;
  c.s0 = light.centre[0] - hs;
  c.t0 = light.centre[1] - ht;
  c.extent_s = 2 * hs;
  c.extent_t = 2 * ht;
  c.height = light.height;
  const int r = c.res, k = std::max(1, supersample);
  c.rgb.assign(static_cast<size_t>(r) * r * 3, 0.0f);
  for (int y = 0; y < r; ++y) {
    for (int x = 0; x < r; ++x) {
      double sum[3] = {0, 0, 0};
      for (int j = 0; j < k; ++j) {
        for (int i = 0; i < k; ++i) {
          const double s = c.s0 + (x + (i + 0.5) / k) * c.extent_s / r;
          const double t = c.t0 + (y + (j + 0.5) / k) * c.extent_t / r;
          const Vec3 v = Radiance(light, f, s, t);
          sum[0] += v.x, sum[1] += v.y, sum[2] += v.z;
        }
      }
      for (int ch = 0; ch < 3; ++ch)
        c.rgb[(size_t(y) * r + x) * 3 + ch] = static_cast<float>(sum[ch] / (k * k));
    }
  }
  c.coeffs.resize(c.rgb.size());
  const size_t texels = size_t(r) * r;
  for (int ch = 0; ch < 3; ++ch) {
    std::span<float> plane(c.coeffs.data() + ch * texels, texels);
    for (size_t m = 0; m < texels; ++m) plane[m] = c.rgb[3 * m + ch];
    Forward2d(WaveletFilter::kHaar, plane, r, r, MaxDepth(r, r));
  }
  return c;
}

std::vector<SourceTerm> SelectSources(const LightCanvas& canvas, double fraction) {
  const int texels = canvas.res * canvas.res;
  const auto coeff = [&](int m, int ch) { return canvas.coeffs[size_t(ch) * texels + m]; };
  std::vector<float> norm(texels);
  std::vector<int> order;
  for (int m = 0; m < texels; ++m) {
    norm[m] = std::hypot(coeff(m, 0), coeff(m, 1), coeff(m, 2));
    if (norm[m] > 0) order.push_back(m);
  }
  const size_t keep = std::min<size_t>(
      order.size(), std::max<size_t>(1, static_cast<size_t>(std::ceil(fraction * texels - 1e-9))));
  std::partial_sort(order.begin(), order.begin() + keep, order.end(),
                    [&](int a, int b) { return norm[a] != norm[b] ? norm[a] > norm[b] : a < b; });
  std::vector<SourceTerm> terms;
  terms.reserve(keep);
  for (size_t j = 0; j < keep; ++j) {
    const int m = order[j];
    terms.push_back({static_cast<uint16_t>(m % canvas.res),
                     static_cast<uint16_t>(m / canvas.res),
                     {coeff(m, 0), coeff(m, 1), coeff(m, 2)}});
  }
  return terms;
}

}  // namespace wavebake
