#pragma once
// The supersampling pattern of the light directions (DESIGN.md §1 "Transport
// entry"): K stratified, jittered directions inside every cubemap texel.
//
// The pattern depends on (cubemap, K, job seed) only — never on the sample —
// so every row of T sees the same directions. Independent per-sample jitter
// turns neighbouring rows into noise and destroys the spatial coherence the
// column transform compresses (DESIGN.md §1: 0.68× vs 0.23× of coefficients).
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "core/directions/cubemap.h"
#include "core/directions/light_domain.h"
#include "core/util/vec3.h"

namespace wavebake {

struct JitterPattern {
  int n = 0;          // cubemap face edge the pattern was made for
  int strata = 0;     // k: strata per texel edge
  int per_texel = 0;  // K = k², directions per texel
  // Unit directions, texel-major: direction k of texel m is at m*K + k.
  // Struct-of-arrays so rays can be fed to Embree packets directly.
  std::vector<float> x, y, z;
  // The 4 corner directions of every texel (unit), at m*4 + c. A texel is the
  // conic hull of its corners, so n·corner ≤ 0 for all 4 means the whole
  // texel is below the horizon of normal n.
  std::vector<Vec3> corners;
  // Ω_m (exact, Cubemap::SolidAngle or PlaneFace::SolidAngle), per texel.
  std::vector<float> solid_angle;

  int texels() const { return static_cast<int>(solid_angle.size()); }
  Vec3 Direction(int m, int k) const {
    const size_t i = static_cast<size_t>(m) * per_texel + k;
    return {x[i], y[i], z[i]};
  }
};

// supersample: requested K, in [1, 256], rounded up to a perfect square k×k.
// Stratum (i, j) of texel (face, tx, ty) is the (s, t) square
// [(tx + i/k)/N, (tx + (i+1)/k)/N] × [(ty + j/k)/N, (ty + (j+1)/k)/N] and its
// direction is jittered uniformly in (s, t) inside it with a generator seeded
// by hash(seed, texel index) alone. Directions are ordered k = j*k + i.
absl::StatusOr<JitterPattern> MakeJitterPattern(const Cubemap& cubemap, int supersample,
                                                uint64_t seed);
// The same stratification and seeding (by texel index m = y·N + x) over the
// one expanded face of a plane light domain.
absl::StatusOr<JitterPattern> MakeJitterPattern(const PlaneFace& face, int supersample,
                                                uint64_t seed);

}  // namespace wavebake
