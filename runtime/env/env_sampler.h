#pragma once
// Importance sampling of a lat-long environment (latlong.h) for the
// Monte-Carlo reference (runtime/reference/reference.h).
//
// The map is the piecewise-constant function EnvRadiance reads (each pixel
// the mean radiance of its footprint) — the same function ResampleToCubemap
// averages into the light cubemap, so the reference and T·L integrate the
// same lighting. Pixels are drawn with probability ∝ Y_p·Ω_p (Y = mean of R,
// G, B, Ω_p the exact pixel solid angle: "luminance × sin θ"), through a 2D
// CDF, marginal over rows then conditional over columns, and the direction is
// uniform in solid angle inside the pixel (so the pdf is exact).
//
// A diffuse receiver sees only max(0, n·ω), which for a tiny, very bright
// source below the horizon wastes most rays. So the 2D CDF is cut into
// coarse blocks (≤ 64 × 32), and per receiver each block's probability is its
// light Σ Y_p Ω_p times an upper bound of max(0, n·ω) over the block: blocks
// entirely below the horizon get none and grazing ones little. Inside a block
// the pixel is still drawn ∝ Y_p Ω_p. Because the bound is ≥ the cosine
// everywhere in the block, every direction with n·ω > 0 and Y > 0 keeps a
// positive pdf: the estimator stays unbiased.
//
// The blocks enter the receiver CDF in the order of a Hilbert curve over the
// 64 × 32 block grid (core/layouts/layout_hilbert_curve.h), so an interval of the
// first uniform is a compact patch of sky: stratifying that uniform (as the
// reference does) stratifies directions.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/util/vec3.h"
#include "runtime/env/env_map.h"

namespace wavebake {

class EnvSampler {
 public:
  // env: lat-long (width = 2·height), borrowed: it must outlive the sampler.
  // Maps narrower than 128 pixels are refined by pixel replication (the same
  // piecewise-constant function), so that blocks stay small for the cosine
  // bound. Memory: one double per (refined) pixel.
  explicit EnvSampler(const EnvMap& env);

  int blocks() const { return static_cast<int>(block_light_.size()); }

  // The block distribution for a receiver with unit normal n, in curve
  // order: cdf[0] = 0, cdf[k+1] = Σ_{k' ≤ k} light·bound(n) of the k'-th
  // block along the curve; cdf.size() must be blocks() + 1. Returns the
  // total (0: no light above the horizon).
  double ReceiverCdf(Vec3 normal, std::span<double> cdf) const;
  // The same with every block's light times bound(centre, radius), an upper
  // bound of the receiver's integrand weight over the block's cap (a glossy
  // lobe's Brdf::CapBound): the blocks the lobe sees get the draws.
  template <typename Bound>
  double ReceiverCdf(const Bound& bound, std::span<double> cdf) const {
    cdf[0] = 0;
    for (int k = 0; k < blocks(); ++k) {
      const int b = curve_[k];
      const double p =
          block_light_[b] > 0 ? block_light_[b] * bound(block_centre_[b], block_radius_[b]) : 0.0;
      cdf[k + 1] = cdf[k] + p;
    }
    return cdf[blocks()];
  }

  struct Draw {
    Vec3 direction;                // unit
    std::array<double, 3> weight;  // L_c(ω) / pdf(ω), pdf in solid angle
    double pdf = 0;
  };
  // One direction from the receiver distribution `cdf` (from ReceiverCdf, with
  // total > 0) and five uniforms in [0, 1): block, row, column, and the
  // position inside the pixel.
  Draw Sample(std::span<const double> cdf, const std::array<double, 5>& u) const;
  // The density in solid angle with which Sample(cdf, ·) draws `direction`
  // (for multiple importance sampling against a BRDF's lobe), and the
  // radiance the map has there.
  double Pdf(std::span<const double> cdf, Vec3 direction) const;
  Vec3 Radiance(Vec3 direction) const;

 private:
  int width_ = 0, height_ = 0;  // of the (possibly refined) map
  int replicate_ = 1;           // refined pixel (x, y) is env pixel (x/r, y/r)
  const EnvMap* env_ = nullptr;
  std::vector<int> block_x_, block_y_;  // pixel boundaries of block columns / rows
  std::vector<double> pixel_cum_;       // inclusive prefix of pixel_weight_ within each row segment
  std::vector<double> segment_;         // Σ pixel_weight_ of row y inside block column bx [H][BX]
  std::vector<double> block_light_;     // Σ Y Ω per block [BY][BX]
  std::vector<Vec3> block_centre_;      // unit direction of each block's (θ, φ) centre
  std::vector<float> block_radius_;     // angular radius bound of each block
  std::vector<int32_t> curve_;          // block id of the k-th block along the Hilbert curve
  std::vector<int32_t> curve_position_;  // inverse of curve_
};

}  // namespace wavebake
