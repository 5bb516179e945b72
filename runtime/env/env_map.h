#pragma once
// Environment lighting as a lat-long radiance map (convention: latlong.h),
// its loading from files or built-ins, lookup by direction and rotation.
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/util/vec3.h"

namespace wavebake {

// Linear RGB radiance, row-major, 3 floats per pixel. A loaded environment is
// lat-long with width == 2 * height; ReadExrImage also uses this type for
// plain images of any size.
struct EnvMap {
  int width = 0, height = 0;
  std::vector<float> rgb;  // [height * width * 3]

  Vec3 Pixel(int x, int y) const {
    const float* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
};

// spec is one of
//   PATH.hdr | PATH.exr   Radiance RGBE (stb_image) or OpenEXR (R, G, B),
//                         lat-long (2:1) or vertical cross (3:4, see env_cross.h,
//                         converted to lat-long on load)
//   builtin:constant      L ≡ 1
//   builtin:sky           procedural sky, sun and area light (env_builtin.h)
// Errors name the file: missing or unreadable file, unknown extension, an
// aspect ratio that is neither layout, and the first pixel (x, y) whose
// radiance is NaN, infinite, negative or above kMaxEnvRadiance.
absl::StatusOr<EnvMap> LoadEnvMap(std::string_view spec);

// The brightest radiance an environment may hold. Relighting sums in float
// (FLT_MAX 3.4e38): a texel is a mean of pixels (≤ max L), an orthonormal
// coefficient of the 6N² texels is at most ‖L‖₂ ≤ √(6N²)·max L ≤ 627·max L
// (N ≤ 256), and a relit value Σ T_m L_m over any set of terms is at most
// ‖T_row‖₂‖L‖₂ ≤ 627·max L (a receiver reflects at most what arrives:
// ‖T_row‖₂ ≤ Σ|T| ≤ 1). 1e30 leaves five orders of magnitude to FLT_MAX for
// the sums' intermediate values and the reference's estimates; real probes,
// an unclipped sun included, stay below 1e10.
inline constexpr float kMaxEnvRadiance = 1e30f;

// Radiance arriving from direction d (need not be normalized): the value of
// the pixel whose footprint holds d. A pixel is the mean radiance over its
// footprint, so the map is piecewise constant; the cubemap resampling
// averages exactly this function and SphereIntegral integrates it, so a
// Monte-Carlo reference that reads EnvRadiance sees the same lighting.
// (Bilinear interpolation would not: it spreads a pole row over a wider cap
// and adds ~8 % to that row's energy.)
Vec3 EnvRadiance(const EnvMap& env, Vec3 d);

// The environment rotated by `degrees` about the vertical (+Y) axis; positive
// is counter-clockwise seen from above (right-hand rule about +Y), so +90°
// carries what was at +X to −Z and what was at −Z to −X. In lat-long this is
// a horizontal shift by −degrees/360 · width pixels; for a fractional shift
// each output pixel is the exact mean of the shifted map over its footprint
// (linear interpolation between two columns), which keeps ∫ L dω. A
// non-finite angle returns the map unchanged.
EnvMap Rotated(const EnvMap& env, double degrees);

}  // namespace wavebake
