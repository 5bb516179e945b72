#pragma once
// BRDFs for glossy relighting (DESIGN.md §1 "What a row holds"; Vollick &
// Lessig §3.7, Ng et al. 2004): one interface for the triple product's BRDF
// factor, which lives in the global frame as a function of the incident
// direction ω_i for the sample's normal n and view ω_o, and for the
// independent Monte-Carlo reference, which importance-samples its lobe.
//
// Eval is f_r alone — the cosine max(0, n·ω_i) is the integrand's, not the
// BRDF's — and is 0 when ω_i or ω_o is below the surface. The models:
//
//   lambert        1/π
//   phong:E        (E+2)/(2π) · max(0, r·ω_i)^E,  r = 2(n·ω_o)n − ω_o (normalized Phong:
//                  albedo 1 at normal incidence)
//   blinn:E        k_E · (n·h)^E,  h = (ω_i + ω_o)/|ω_i + ω_o|,
//                  k_E = (E+2)(E+4) / (8π (2^(−E/2) + E)) (albedo 1 at normal incidence)
//   ggx:A          D(h) G₂(ω_i, ω_o) / (4 (n·ω_i)(n·ω_o)), Trowbridge–Reitz / GGX D of
//                  width α = A, height-correlated Smith G₂ (core/products/ggx.h), no Fresnel (F =
//                  1)
//
// Colour is the sample's albedo, applied outside (DESIGN.md §1).
#include <memory>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/util/vec3.h"

namespace wavebake {

// Directions with cos(angle to axis) < cos_angle have f_r · cos θ_i below a
// chosen fraction of the lobe's peak: a texel wholly outside can be skipped.
struct LobeCone {
  Vec3 axis;
  float cos_angle = -1;  // −1: the whole sphere
};

class Brdf {
 public:
  virtual ~Brdf() = default;
  // n, wo, wi unit; wo points away from the surface (towards the viewer).
  virtual double Eval(Vec3 n, Vec3 wo, Vec3 wi) const = 0;
  // A direction from the lobe for two uniforms in [0, 1); it may lie below
  // the surface (Eval = 0 there). Pdf is its density in solid angle.
  virtual Vec3 Sample(Vec3 n, Vec3 wo, double u1, double u2) const = 0;
  virtual double Pdf(Vec3 n, Vec3 wo, Vec3 wi) const = 0;
  // The cone outside which f_r · cos < relative · (the lobe's maximum).
  virtual LobeCone Support(Vec3 n, Vec3 wo, double relative) const = 0;
  // An upper bound of f_r(ω) · max(0, n·ω) over the cap of angular radius
  // `radius` around the unit direction `centre` (the reference's per-block
  // importance, runtime/env/env_sampler.h).
  virtual double CapBound(Vec3 n, Vec3 wo, Vec3 centre, double radius) const = 0;
  // Σ_q f_r(n, wo, ω_q) · max(0, n·ω_q) over `count` unit directions given
  // as coordinate arrays: a texel's quadrature (runtime/glossy/brdf_slices.h), the
  // hot loop of projecting slices, so the models set up their lobe once.
  virtual double SumOverDirections(Vec3 n, Vec3 wo, const float* x, const float* y, const float* z,
                                   int count) const;
  virtual bool ViewDependent() const { return true; }
  virtual std::string Name() const = 0;  // the spec ParseBrdf reads back
};

// "lambert" | "phong:E" | "blinn:E" (E in (0, 100000]) | "ggx:A" (A in (0, 1]).
// Errors name the `brdf` field.
absl::StatusOr<std::unique_ptr<Brdf>> ParseBrdf(std::string_view spec);

// Upper bound of max(0, n·ω) over the cap of angular radius r around c.
double CosineOverCap(Vec3 n, Vec3 c, double r);

// Unit t, b with (t, b, axis) right-handed and orthonormal.
void OrthonormalFrame(Vec3 axis, Vec3& t, Vec3& b);
// The mirror direction of w about the unit vector n: 2(n·w)n − w.
inline Vec3 Reflect(Vec3 w, Vec3 n) { return n * (2 * Dot(n, w)) - w; }

}  // namespace wavebake
