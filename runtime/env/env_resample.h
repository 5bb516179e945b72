#pragma once
// The lighting vector L of B = T·L (DESIGN.md §1 "Relighting"): the
// environment resampled onto the light cubemap.
#include <vector>

#include "core/directions/cubemap.h"
#include "runtime/env/env_map.h"

namespace wavebake {

// RGB per light index m, [3 * M]: the mean radiance of the environment over
// texel m, Σ_p L_p |p ∩ m| / Ω_m with the pixel/texel overlaps of
// sphere_overlap.h. T already carries Ω_m, so L_m must be the texel's
// *average* radiance: point sampling would miss a source smaller than a
// texel (a sun, a lamp) or blow it up to the texel's size. A constant map
// stays exactly constant and Σ_m L_m Ω_m = SphereIntegral. The result does
// not depend on the number of threads. To resample many maps of one size
// (a rotating environment), build one SphereOverlap and reuse it.
std::vector<float> ResampleToCubemap(const EnvMap& env, const Cubemap& cube);

// The naive baseline, for tests and benchmarks only: EnvRadiance at each
// texel centre.
std::vector<float> PointSampleToCubemap(const EnvMap& env, const Cubemap& cube);

// ∫ L dω of one channel (0 = R, 1 = G, 2 = B) on the lat-long grid itself,
// Σ pixel · its exact solid angle (latlong.h): the integral of EnvRadiance.
double SphereIntegral(const EnvMap& env, int channel);

}  // namespace wavebake
