#pragma once
// The BRDF factor of the triple product, one slice per sample (Vollick &
// Lessig §3.7, Ng et al. 2004): in the global frame, as a function of the
// incident direction ω for the sample's normal n and view ω_o,
//
//   ρ_x(ω) = f_r(n, ω_o, ω) · max(0, n·ω)        (the cosine absorbed, V&L Eq. 1)
//
// on the bake's cubemap, texel m holding Ω_m · (1/Q) Σ_q ρ_x(ω_q), its mean
// over Q stratified, jittered directions (a jitter pattern of the store's
// seed with Q per texel), projected into the row basis per face and cut to
// its `terms` largest coefficients (non-linear approximation; |c| is the L²
// importance in the orthonormal basis). Q need not be the bake's K: V is a
// texel mean already, and a lobe that varies by 30 % across a 2.8° texel
// (phong:32 at N = 32) needs more than K = 4 points for its own mean — on
// sphere-plane under grace the dense path's error against the reference
// drops from 5.0 % (Q = 4) to 4.35 % (Q = 16), 4.31 % at Q = 64.
//
// Texels that the lobe's cone (Brdf::Support at `lobe_cutoff` of the peak)
// misses, or that lie wholly below the horizon, are 0 and cost nothing;
// faces with no texel left are skipped. A slice depends on (n, ω_o) only, so
// a view and a BRDF cost one projection per sample, then any number of
// frames.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/directions/jitter_pattern.h"
#include "core/layouts/samples.h"
#include "core/products/brdf.h"

namespace wavebake {

struct SliceOptions {
  int terms = 256;            // kept coefficients per slice; 0 = every nonzero one
  int quadrature = 16;        // directions per texel (jittered k×k strata); 0 = the store's K
  double lobe_cutoff = 1e-5;  // of the lobe's peak (f_r·cos)
};

struct BrdfSlices {
  int light_res = 0;
  std::vector<int64_t> first;   // [cells + 1]; masked cells have empty slices
  std::vector<uint32_t> index;  // row-basis index, increasing within a slice
  std::vector<float> value;
  double seconds = 0;

  std::span<const uint32_t> Index(int cell) const {
    return {index.data() + first[cell], static_cast<size_t>(first[cell + 1] - first[cell])};
  }
  std::span<const float> Value(int cell) const {
    return {value.data() + first[cell], static_cast<size_t>(first[cell + 1] - first[cell])};
  }
  size_t bytes() const {
    return first.size() * sizeof(int64_t) + index.size() * (sizeof(uint32_t) + sizeof(float));
  }
};

// views: per grid cell, the unit direction from the sample towards the eye
// (ignored for masked cells). pattern: the quadrature's directions (N of
// the store, Q per texel; see BrdfQuadrature).
// Errors name the mismatched size.
absl::StatusOr<BrdfSlices> ProjectBrdfSlices(const Brdf& brdf, const SampleSet& samples,
                                             std::span<const Vec3> views,
                                             const JitterPattern& pattern,
                                             const SliceOptions& options = {});

// The `n` entries of largest |value| (ties: the lower index), appended to
// out_index/out_value in increasing index order; all of them if n ≤ 0 or
// there are no more than n. index must be increasing. The cut of every
// slice (ProjectBrdfSlices, and the incremental material editor).
void KeepLargest(std::span<const uint32_t> index, std::span<const float> value, int n,
                 std::vector<uint32_t>& out_index, std::vector<float>& out_value);

// Every cell's slice cut to its `n` largest coefficients (KeepLargest).
BrdfSlices CutSlices(const BrdfSlices& slices, int n);

// The quadrature pattern of the slices: the store's cubemap and seed, Q =
// options.quadrature directions per texel (0: the store's K).
absl::StatusOr<JitterPattern> BrdfQuadrature(int light_res, int store_supersample, uint64_t seed,
                                             const SliceOptions& options);

// One sample's slice texel by texel, before the row transform and the cut:
// Ω_m (1/K) Σ_k f_r max(0, n·ω_k) for every texel m of the cubemap (the
// pixel-domain BRDF factor of the dense glossy path, runtime/reference/dense_trace.h).
class BrdfTexels {
 public:
  explicit BrdfTexels(const JitterPattern* pattern);  // borrowed
  // cube [6N²] must be zero on entry; returns the faces it wrote.
  std::array<bool, 6> Evaluate(const Brdf& brdf, Vec3 normal, Vec3 view, double lobe_cutoff,
                               std::span<float> cube) const;
  // The same, then the row transform of every written face: the slice
  // before the cut.
  std::array<bool, 6> Slice(const Brdf& brdf, Vec3 normal, Vec3 view, double lobe_cutoff,
                            std::span<float> cube) const;

 private:
  const JitterPattern* pattern_;
  // Each texel as a cap: centre, cos/sin of the angular radius holding its
  // corners (and so, the texel being their conic hull, all of it), radius.
  std::vector<Vec3> centre_;
  std::vector<float> cos_r_, sin_r_, radius_;
};

}  // namespace wavebake
