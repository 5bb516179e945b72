#pragma once
// Per-band incremental (PBI) relighting for lighting sequences: Overbeck,
// "Exploiting temporal coherence for real-time all-frequency relighting",
// ch. 6 (Fig. 6.1) with the simple per-band test of §6.2.2.
//
// The row basis is split into bands of equal support (runtime/relight/row_basis.h
// RowBand; §6.1). Every frame, for each band k, the §6.2.2 test compares
// ‖L_new − L̃‖_k with ‖L_new‖_k (area-weighted L1 over the band's
// coefficients and channels; the thesis found L1 best, L2 similar): if the
// residual is smaller the band is updated incrementally (Eq. 4.2–4.5: the
// chosen wavelets carry ΔL_j = L_new_j − L̃_j and the band image gets
// B_k += T ΔL), otherwise it is reset (L̃ and B_k of the band zeroed, the chosen
// wavelets carry L_new_j, Eq. 4.1). The frame's n wavelets are the top n over
// all bands by area-weighted magnitude of what each would carry (|ΔL_j| in
// incremental bands, |L_new_j| in reset ones; §6.1 and Ng et al. 2003), and
// every chosen j sets L̃_j = L_new_j. B = Σ_k B_k (line 20), × albedo.
//
// Static lighting is a fixed point that is reached exactly: every frame
// moves n more residual coefficients into L̃, so after ⌈nonzeros/n⌉ + 1
// frames L̃ = L and B is the full-lighting image (up to float rounding of
// the accumulated B_k).
//
// IncrementalPolicy::kBasic is Overbeck's basic incremental (BI, ch. 4,
// Eq. 4.2–4.5) run through the same code: one band holding every basis
// function that is always incremental, so nothing is ever reset. It is the
// baseline of Fig. 6.2: a global change of the lighting (a rotation touches
// every wavelet) outruns the n-term budget and ghosts of earlier lighting
// linger in the image (§5, Fig. 5.1), which PBI's per-band resets avoid.
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/relighter.h"

namespace wavebake {

enum class IncrementalPolicy {
  kPerBand,  // PBI: bands by support size, the §6.2.2 test per band per frame
  kBasic,    // BI: one band, always incremental, never reset
};

class IncrementalRelighter {
 public:
  // relighter is borrowed and must outlive this object; terms > 0 is the
  // wavelet budget per frame.
  static absl::StatusOr<IncrementalRelighter> Create(
      Relighter* relighter, int terms, IncrementalPolicy policy = IncrementalPolicy::kPerBand);

  // One frame. lighting: the frame's complete L in the row basis of the
  // relighter's light resolution (an error otherwise). rgb_out: [W*H*3],
  // × albedo, masked cells NaN.
  absl::Status Frame(const LightingCoefficients& lighting, std::span<float> rgb_out);

  // Forgets all previous frames: the next one starts from L̃ = 0.
  void Reset();

  struct BandStats {
    bool incremental = false;  // the §6.2.2 decision of the last frame (always, kBasic)
    int terms = 0;             // wavelets the band got in the last frame
    double residual_l1 = 0;    // ‖L_new − L̃‖ before the update
    double lighting_l1 = 0;    // ‖L_new‖
  };
  const std::vector<BandStats>& last_frame() const { return stats_; }
  // L̃ after the last frame, [3 * 6N²] in the row basis.
  std::span<const float> approximation() const { return approx_; }
  int bands() const { return static_cast<int>(stats_.size()); }

 private:
  IncrementalRelighter() = default;
  void DecideBands(const LightingCoefficients& lighting);
  void ChooseLights(const LightingCoefficients& lighting);
  void UpdateBandImages();

  Relighter* relighter_ = nullptr;
  int terms_ = 0;
  IncrementalPolicy policy_ = IncrementalPolicy::kPerBand;
  std::vector<uint8_t> band_of_;                 // [M]
  std::vector<float> support_;                   // [M] SupportSolidAngles
  std::vector<float> approx_;                    // L̃, [3M]
  std::vector<std::vector<float>> band_images_;  // B_k before albedo, [bands][W*H*3]
  std::vector<BandStats> stats_;                 // [bands]
  // Per-frame scratch.
  std::vector<float> importance_;                       // [M]
  std::vector<std::vector<WaveletLight>> band_lights_;  // [bands]
  std::vector<float> delta_image_;                      // [W*H*3]
};

}  // namespace wavebake
