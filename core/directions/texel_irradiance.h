#pragma once
// The exact cosine-weighted solid angle of a cubemap texel,
//
//   I_m(n) = (1/π) ∫_{texel m} max(0, n·ω) dω,
//
// the transport entry of a texel that is visible everywhere (DESIGN.md §1
// with V ≡ 1). A texel edge is a straight segment on the cube face, hence a
// great-circle arc, so the texel is a spherical quadrilateral and Lambert's
// formula for polygons gives the integral in closed form (Arvo 1995,
// "Applications of irradiance tensors", Eq. 2): ∫_P ω dω = ½ Σ_i Θ_i û_i,
// Θ_i the arc length of edge i and û_i the unit normal of its plane.
//
// When all four corners are above the horizon of n, so is the whole texel
// (the conic hull of its corners) and the clamp is inactive: I_m(n) = n·Φ_m
// with Φ_m = (1/π)∫ ω dω a constant vector per texel, computed once per job.
// A texel the horizon crosses is clipped to the hemisphere first.
#include <vector>

#include "core/directions/cubemap.h"
#include "core/util/vec3.h"

namespace wavebake {

// Φ_m for every texel m (index order), computed in double, stored as float.
std::vector<Vec3> TexelIrradianceVectors(const Cubemap& cubemap);

// I_m(n) for any unit n: the texel clipped to n·ω ≥ 0, then Lambert's formula,
// in double. 0 for a texel entirely below the horizon.
double ClippedTexelIrradiance(const Cubemap& cubemap, int m, Vec3 n);
// The same, half the work: `into` is any direction inside the texel (Φ_m
// will do), which orients the clipped part's Lambert vector.
double ClippedTexelIrradiance(const Cubemap& cubemap, int m, Vec3 n, Vec3 into);

}  // namespace wavebake
