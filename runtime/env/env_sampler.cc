#include "runtime/env/env_sampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/layouts/layout_hilbert_curve.h"
#include "runtime/env/latlong.h"

namespace wavebake {
namespace {

constexpr int kMinWidth = 128;
constexpr int kBlockColumns = 64, kBlockRows = 32;

double MeanRgb(Vec3 v) { return (double{v.x} + v.y + v.z) / 3; }

// Great-circle radius bound of the (θ, φ) rectangle around its centre: from
// the centre go along the meridian (≤ Δθ/2), then along the parallel
// (≤ sin θ_max · Δφ/2); the geodesic is no longer than that path.
double RadiusBound(double theta0, double theta1, double phi_span) {
  const double sin_max = (theta0 <= std::numbers::pi / 2 && theta1 >= std::numbers::pi / 2)
                             ? 1.0
                             : std::max(std::sin(theta0), std::sin(theta1));
  return std::min(std::numbers::pi, (theta1 - theta0) / 2 + sin_max * phi_span / 2 + 1e-6);
}

// Upper bound of max(0, n·ω) over the cap of angular radius r around the
// unit direction c.
double CosineBound(Vec3 n, Vec3 c, double r) {
  const double alpha = std::acos(std::clamp(double{Dot(n, c)}, -1.0, 1.0));
  if (alpha <= r) return 1;
  if (alpha - r >= std::numbers::pi / 2) return 0;
  return std::cos(alpha - r);
}

Vec3 Direction(double theta, double phi) {
  const double st = std::sin(theta);
  return {static_cast<float>(st * std::sin(phi)), static_cast<float>(std::cos(theta)),
          static_cast<float>(-st * std::cos(phi))};
}

}  // namespace

EnvSampler::EnvSampler(const EnvMap& env) : env_(&env) {
  replicate_ = std::max(1, (kMinWidth + env.width - 1) / std::max(env.width, 1));
  width_ = env.width * replicate_;
  height_ = env.height * replicate_;
  // width_ ≥ 128 and height_ ≥ 64 after refinement: always 64 × 32 blocks.
  const int bx_count = kBlockColumns, by_count = kBlockRows;
  curve_ = HilbertCurveCells(bx_count, by_count);
  curve_position_.resize(curve_.size());
  for (size_t k = 0; k < curve_.size(); ++k) curve_position_[curve_[k]] = static_cast<int32_t>(k);
  for (int i = 0; i <= bx_count; ++i)
    block_x_.push_back(static_cast<int>(int64_t{i} * width_ / bx_count));
  for (int j = 0; j <= by_count; ++j)
    block_y_.push_back(static_cast<int>(int64_t{j} * height_ / by_count));

  pixel_cum_.resize(static_cast<size_t>(width_) * height_);
  segment_.resize(static_cast<size_t>(height_) * bx_count);
  for (int y = 0; y < height_; ++y) {
    const double omega = LatLongPixelSolidAngle(y, width_, height_);
    for (int bx = 0; bx < bx_count; ++bx) {
      double cum = 0;
      for (int x = block_x_[bx]; x < block_x_[bx + 1]; ++x) {
        cum += MeanRgb(env.Pixel(x / replicate_, y / replicate_)) * omega;
        pixel_cum_[static_cast<size_t>(y) * width_ + x] = cum;
      }
      segment_[static_cast<size_t>(y) * bx_count + bx] = cum;
    }
  }
  for (int by = 0; by < by_count; ++by) {
    const double theta0 = std::numbers::pi * block_y_[by] / height_,
                 theta1 = std::numbers::pi * block_y_[by + 1] / height_;
    for (int bx = 0; bx < bx_count; ++bx) {
      double light = 0;  // summed in row order, exactly as Sample walks the rows
      for (int y = block_y_[by]; y < block_y_[by + 1]; ++y) {
        light += segment_[static_cast<size_t>(y) * bx_count + bx];
      }
      const double phi0 = std::numbers::pi * (2.0 * block_x_[bx] / width_ - 1);
      const double phi1 = std::numbers::pi * (2.0 * block_x_[bx + 1] / width_ - 1);
      block_light_.push_back(light);
      block_centre_.push_back(Direction((theta0 + theta1) / 2, (phi0 + phi1) / 2));
      block_radius_.push_back(static_cast<float>(RadiusBound(theta0, theta1, phi1 - phi0)));
    }
  }
}

double EnvSampler::ReceiverCdf(Vec3 normal, std::span<double> cdf) const {
  cdf[0] = 0;
  for (int k = 0; k < blocks(); ++k) {
    const int b = curve_[k];
    const double p = block_light_[b] > 0
                         ? block_light_[b] * CosineBound(normal, block_centre_[b], block_radius_[b])
                         : 0.0;
    cdf[k + 1] = cdf[k] + p;
  }
  return cdf[blocks()];
}

EnvSampler::Draw EnvSampler::Sample(std::span<const double> cdf,
                                    const std::array<double, 5>& u) const {
  const int bx_count = static_cast<int>(block_x_.size()) - 1;
  // Block: the first whose cumulative probability exceeds u·total, so blocks
  // of probability 0 are never drawn.
  const double total = cdf[blocks()];
  int k = static_cast<int>(std::upper_bound(cdf.begin() + 1, cdf.end(), u[0] * total) -
                           (cdf.begin() + 1));
  // u·total can round up to total: fall back to the last block with light.
  for (k = std::min(k, blocks() - 1); cdf[k + 1] == cdf[k];) --k;
  const int b = curve_[k];
  const int bx = b % bx_count, by = b / bx_count;
  // Row inside the block ∝ its light, then column inside the row segment.
  const double row_target = u[1] * block_light_[b];
  int y = block_y_[by];
  for (double acc = 0; y < block_y_[by + 1] - 1; ++y) {
    acc += segment_[static_cast<size_t>(y) * bx_count + bx];
    if (acc > row_target) break;
  }
  while (segment_[static_cast<size_t>(y) * bx_count + bx] == 0) --y;  // rounding at the end
  const double* row = pixel_cum_.data() + static_cast<size_t>(y) * width_;
  const double col_target = u[2] * segment_[static_cast<size_t>(y) * bx_count + bx];
  int x = static_cast<int>(
      std::upper_bound(row + block_x_[bx], row + block_x_[bx + 1] - 1, col_target) - row);
  // Uniform in solid angle inside the pixel: cos θ and φ uniform.
  const double c0 = std::cos(std::numbers::pi * y / height_),
               c1 = std::cos(std::numbers::pi * (y + 1) / height_);
  const double theta = std::acos(std::clamp(c0 - u[3] * (c0 - c1), -1.0, 1.0));
  const double phi = std::numbers::pi * (2 * (x + u[4]) / width_ - 1);
  // pdf = P(block) · (Y_p Ω_p / light_b) / Ω_p, so L_c / pdf =
  // L_c · light_b / (P(block) · Y_p) with P(block) = (cdf[b+1] − cdf[b]) / total.
  const Vec3 radiance = env_->Pixel(x / replicate_, y / replicate_);
  const double scale = block_light_[b] * total / ((cdf[k + 1] - cdf[k]) * MeanRgb(radiance));
  return {Direction(theta, phi),
          {radiance.x * scale, radiance.y * scale, radiance.z * scale},
          1 / scale};
}

Vec3 EnvSampler::Radiance(Vec3 direction) const {
  const LatLong ll = DirectionToLatLong(direction);
  const int x = std::clamp(static_cast<int>(ll.u * width_), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(ll.v * height_), 0, height_ - 1);
  return env_->Pixel(x / replicate_, y / replicate_);
}

double EnvSampler::Pdf(std::span<const double> cdf, Vec3 direction) const {
  const double total = cdf[blocks()];
  if (!(total > 0)) return 0;
  const LatLong ll = DirectionToLatLong(direction);
  const int x = std::clamp(static_cast<int>(ll.u * width_), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(ll.v * height_), 0, height_ - 1);
  const int bx =
      static_cast<int>(std::upper_bound(block_x_.begin(), block_x_.end(), x) - block_x_.begin()) -
      1;
  const int by =
      static_cast<int>(std::upper_bound(block_y_.begin(), block_y_.end(), y) - block_y_.begin()) -
      1;
  const int bx_count = static_cast<int>(block_x_.size()) - 1;
  const int b = by * bx_count + bx;
  if (!(block_light_[b] > 0)) return 0;
  const int k = curve_position_[b];
  // P(block) · (Y_p Ω_p / light_b) / Ω_p, as Sample draws it.
  const double p_block = (cdf[k + 1] - cdf[k]) / total;
  return p_block * MeanRgb(env_->Pixel(x / replicate_, y / replicate_)) / block_light_[b];
}

}  // namespace wavebake
