#pragma once
// Light propagation in the wavelet domain (Sun & Ramamoorthi 2009, Eq. 30
// and §5.3.1): the Haar coefficients on an N×N target face of a light whose
// R×R source image is seen through the per-axis affine map q = s·v + o
// (Eq. 29: a point at distance z from a light plane sees the plane at
// q = x + z·v), computed from the source's coefficients without going
// through pixels:
//
//   L_k = Σ_i F_i D_ik,   D_ik = D_{i_x k_x}(s_x, o_x) · D_{i_y k_y}(s_y, o_y)   (Eq. 26)
//
// in the two steps of §5.3.1 that make it O(n log N) rather than the
// O(n log² N) of the 2D coefficients:
//
//   step 1  Z_{i_y k_x} = Σ_{i_x} F_{i_x i_y} D_{i_x k_x}
//   step 2  L_{k_x k_y} = Σ_{i_y} Z_{i_y k_x} D_{i_y k_y}
//
// Both bases are non-standard Haar, Mallat layout (the row transform's;
// factors in core/products/haar_affine.h). Every non-standard target but the scaling
// function has a wavelet factor, whose couplings are sparse (only wavelets
// with a source breakpoint inside are nonzero), so step 2 runs along the
// axis whose target factor is a wavelet: the y-first order of the steps
// above for targets with a ψ in y, the x-first order (steps swapped) for
// the others. Coefficients are the discrete orthonormal ones of the images
// (row-transform scale): L = (N/R)·Σ F D, since a discrete n×n coefficient
// is n times the continuous one.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/products/coupling_table.h"
#include "core/products/haar_affine.h"

namespace wavebake {

// One source coefficient: Mallat position (x, y) in the R×R source image.
struct SourceTerm {
  uint16_t x = 0, y = 0;
  std::array<float, 3> rgb{};
};

// q = s·v + o on each axis, v ∈ [0,1] on the target, q ∈ [0,1] on the source.
struct AffineMap2d {
  double s_x = 1, o_x = 0, s_y = 1, o_y = 0;
};

class AffinePropagator {
 public:
  // sources: any subset of the source coefficients (the source-level
  // truncation of §5.3.3 happens before); table: null computes the
  // couplings (SourceCouplings), else they are looked up (memory-based
  // approach, table made for source_res × target_res).
  AffinePropagator(std::span<const SourceTerm> sources, int source_res, int target_res,
                   const CouplingTable* table = nullptr);

  int source_res() const { return source_res_; }
  int target_res() const { return target_res_; }

  // rgb_out[3j + c] = L of target Mallat index targets[j] (= y·N + x).
  // Not thread-safe (scratch); one propagator per thread.
  void Propagate(const AffineMap2d& map, std::span<const uint16_t> targets,
                 std::span<float> rgb_out);

 private:
  // The sources grouped by one of their factors.
  struct Axis {
    std::vector<uint16_t> factor;  // distinct factor ids of this axis
    // Per distinct factor, this frame: its couplings (computed into `owned`,
    // or views of the table).
    std::vector<std::vector<Coupling1d>> owned;
    std::vector<std::span<const Coupling1d>> couplings;
  };
  struct Term {
    uint16_t x_slot, y_slot;
    std::array<float, 4> rgb;
  };
  using Rgb4 = std::array<float, 4>;
  struct Bucket {  // a (source slot, coupling) of one target factor
    uint16_t slot;
    float value;
  };

  void Couple(Axis& axis, double s, double o);
  // partial[slot · F + k] += rgb · D over the terms' couplings on `along`,
  // grouped by their slot on the other axis.
  void Accumulate(const Axis& along, bool along_x, std::vector<Rgb4>& partial);
  // buckets of target factor k: the (slot, D) of every coupling of `axis`.
  void Invert(const Axis& axis, std::vector<uint32_t>& first, std::vector<Bucket>& buckets);
  void Clear(const Axis& along, bool along_x, std::vector<Rgb4>& partial);

  int source_res_, target_res_, target_factors_;
  const CouplingTable* table_;
  Axis x_, y_;
  std::vector<Term> terms_;
  std::vector<uint16_t> target_x_, target_y_;  // factor ids of each target Mallat index
  std::vector<bool> target_y_wavelet_;
  // Per frame: Z by y slot (x-first order) and by x slot (y-first order).
  std::vector<Rgb4> z_by_y_, z_by_x_;
  std::vector<uint32_t> first_x_, first_y_;
  std::vector<Bucket> buckets_x_, buckets_y_;
};

}  // namespace wavebake
