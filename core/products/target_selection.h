#pragma once
// Target-level truncation with the constant-light heuristic (Sun &
// Ramamoorthi §5.3.3, Eq. 32): which of the N² coefficients L_k of the
// light on a sample's face to propagate, chosen without computing them.
// The heuristic light is the DC of the source — a constant over the light's
// canvas — whose image on the face is the rectangle R = [ax, bx] × [ay, by]
// (clipped to [0,1]²), so its prediction
//
//   L̃_k = ∫ 1_R Ψ_k  = ã(k_x) · ã(k_y)    (ã: 1D coefficients of an interval)
//
// costs two 1D evaluations. A target whose support misses R is 0 for any
// light and is never picked. Of the others, the `budget` largest |L̃_k| are
// kept; ties — the wavelets wholly inside R, whose prediction is 0 while a
// textured light's is not — go coarse level first, then in Mallat order.
#include <cstdint>
#include <vector>

namespace wavebake {

class TargetSelector {
 public:
  explicit TargetSelector(int n);  // face texels per edge, a power of two

  // Appends the chosen Mallat indices (y·N + x) to `out` (after clearing it),
  // in no particular order. An empty rectangle chooses nothing.
  void Select(double ax, double bx, double ay, double by, int budget, std::vector<uint16_t>& out);

  // The prediction L̃ of Mallat index m for the rectangle (for tests).
  double Prediction(double ax, double bx, double ay, double by, int m) const;

 private:
  struct Scored {
    float score;
    uint16_t index;
  };
  int n_, levels_;
  std::vector<Scored> scored_;
};

}  // namespace wavebake
