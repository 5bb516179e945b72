#pragma once
// The lighting side of relighting (DESIGN.md §1 "Relighting"; 4D paper §4.5):
// environment → the bake's cubemap → the bake's row transform → the n most
// important wavelet lights (non-linear approximation, Ng et al. 2003).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "runtime/env/sphere_overlap.h"

namespace wavebake {

struct EnvMap;

// The lighting vector L in the row basis: rgb[3*m + c] is the coefficient of
// basis function m (= column m of T) in channel c.
struct LightingCoefficients {
  int light_res = 0;  // N
  WaveletFilter row_filter = WaveletFilter::kHaar;
  std::vector<float> rgb;  // [3 * 6N²]

  int size() const { return static_cast<int>(rgb.size() / 3); }
};

// One term w^i of Eq. 3–8: column i of T and its RGB weight.
struct WaveletLight {
  uint32_t column = 0;
  std::array<float, 3> weight{};
};

// A non-linear approximation of L: at most n terms, most important first.
struct WaveletLights {
  int light_res = 0;
  std::vector<WaveletLight> lights;
};

// cube_rgb: per texel mean radiance, [3 * 6N²] (runtime/env/env_resample.h
// ResampleToCubemap), transformed per face with RowTransformCube.
LightingCoefficients ProjectLighting(std::span<const float> cube_rgb, int light_res,
                                     WaveletFilter row_filter);

// LoadEnvMap result → ResampleToCubemap → ProjectLighting. Errors: light_res
// not a power of two in [1, 256], an env map that is not lat-long.
absl::StatusOr<LightingCoefficients> LightingFromEnv(const EnvMap& env, int light_res,
                                                     WaveletFilter row_filter);

// LightingFromEnv for many maps of one size, the frames of a rotating
// environment: the pixel/texel overlap (~40 ms at N = 32, bench_env_resample)
// is built once, and each map then costs one sparse product (~0.1 ms) and the
// row transform. Results are identical to LightingFromEnv's.
class EnvProjector {
 public:
  // Same errors as LightingFromEnv, naming light_res or the env size.
  static absl::StatusOr<EnvProjector> Create(int env_width, int env_height, int light_res,
                                             WaveletFilter row_filter);
  // env must have the size given to Create (an error names it otherwise).
  absl::StatusOr<LightingCoefficients> Project(const EnvMap& env) const;

 private:
  EnvProjector(SphereOverlap overlap, int width, int height, int light_res, WaveletFilter filter)
      : overlap_(std::move(overlap)),
        width_(width),
        height_(height),
        light_res_(light_res),
        row_filter_(filter) {}
  SphereOverlap overlap_;
  int width_, height_, light_res_;
  WaveletFilter row_filter_;
};

// Importance of term m for the area-weighted selection of Ng et al. 2003:
//   |L_m|₂ · Ω(support of basis function m)
// with |L_m|₂ the Euclidean norm of the RGB coefficient (never cancels
// between channels, unlike a signed luminance; a grey light counts √3 × its
// value) and Ω the solid angle of the basis function's support
// (runtime/relight/row_basis.h SupportSolidAngles): a coarse wavelet moves light over
// a large solid angle, so an equally large coefficient there matters more.
// `support` may be empty (then it is computed); pass SupportSolidAngles(N) to
// select per frame without recomputing it.
std::vector<float> LightImportance(const LightingCoefficients& lighting,
                                   std::span<const float> support = {});

// The `terms` most important nonzero terms (ties: lower column first), sorted
// by decreasing importance. terms ≥ 6N² keeps every nonzero coefficient.
// Error: terms ≤ 0.
absl::StatusOr<WaveletLights> SelectWaveletLights(const LightingCoefficients& lighting, int terms,
                                                  std::span<const float> support = {});

// Every coefficient as a light, zeros included, in column order: the
// non-approximated lighting (tests, dense comparisons).
WaveletLights AllWaveletLights(const LightingCoefficients& lighting);

}  // namespace wavebake
