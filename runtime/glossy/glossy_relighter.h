#pragma once
// Glossy, view-dependent relighting of a visibility store by the Haar triple
// product (Vollick & Lessig §§3.4–3.7; Ng et al. 2004; DESIGN.md §1 "Per-
// sample lighting"):
//
//   B(x) = albedo(x) · Σ_{i,j,k} C(i, j, k) L_i V_j(x) ρ_k(x) = albedo(x) · ⟨V(x), W(x)⟩,
//   W(x) = P(L · ρ_x),  W_j(x) = Σ_{i,k} C(i, j, k) L_i ρ_k(x)
//
// L: the frame's n-term lighting; V(x): the store's visibility rows decoded
// once (runtime/relight/sample_rows.h); ρ_x: the sample's BRDF slice for its normal
// and view (runtime/glossy/brdf_slices.h). A frame builds L's factor once (dense
// coefficients, parent sums: O(M)); then per cell SampleRows::Apply asks,
// face by face where ρ_x has terms, for W at the terms the row V(x) has, and
// the tree algorithm forms just those (HaarProduct::Combine): O(|ρ_x| +
// |L ∩ ρ_x| · levels + |V(x)|). The ρ-side numbers of every W_j (ĝ, g_j and
// the square's other two g) do not change with the lighting: they are
// gathered once per slices (HaarProduct::Gather, 16 bytes per row entry).
// Nothing per frame decodes the 4D columns.
#include <memory>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/products/haar_product.h"
#include "runtime/glossy/brdf_slices.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/sample_rows.h"

namespace wavebake {

// L's factor for the products of a frame: the lights' weights in a dense
// row-basis cube (repeated columns add up).
HaarFactor LightingFactor(const WaveletLights& lights);

class GlossyRelighter {
 public:
  // rows is borrowed and must outlive the relighter; slices, samples and
  // rows must be for one grid and one light resolution (errors name the
  // mismatch). threads: 0 = all cores; the image does not depend on it.
  static absl::StatusOr<GlossyRelighter> Create(const SampleRows* rows, const SampleSet& samples,
                                                BrdfSlices slices, int threads = 0);

  int cells() const { return rows_->cells(); }
  int light_res() const { return rows_->light_res(); }
  const BrdfSlices& slices() const { return slices_; }
  // A new BRDF or view (same grid and N, checked).
  absl::Status SetSlices(BrdfSlices slices);

  // [W·H·3] = albedo · ⟨V, P(L·ρ)⟩, masked cells NaN.
  void Relight(const WaveletLights& lights, std::span<float> rgb_out);
  // The same before the albedo, for any factor and any slices of this grid
  // (linear in both: the incremental material editor feeds it deltas; slices
  // other than slices() are gathered on the fly). Masked cells get 0.
  void Transport(const HaarFactor& lighting, const BrdfSlices& slices, std::span<float> rgb_out);
  // rgb_out = transport_rgb × albedo (NaN in masked cells); may alias.
  void ApplyAlbedo(std::span<const float> transport_rgb, std::span<float> rgb_out) const;

 private:
  struct Scratch {
    explicit Scratch(int n) : product(n) {}
    HaarProduct product;
    std::vector<float> weights;
  };
  GlossyRelighter() = default;
  const SampleRows* rows_ = nullptr;
  BrdfSlices slices_;
  std::vector<float> albedo_;  // [cells·3], NaN where masked
  std::vector<uint8_t> masked_;
  int threads_ = 0;
  std::vector<std::unique_ptr<Scratch>> scratch_;  // per worker
  std::vector<HaarProduct::Gathered> gathered_;    // per row entry, for slices_
  void GatherSlices();
};

}  // namespace wavebake
