#pragma once
// Subband bookkeeping for Mallat-layout wavelet coefficients (DESIGN.md §1
// "Column transform", "Scaling and quantization"; 4D paper §4.2–4.3).
#include <vector>

#include "core/bake/bake_params.h"

namespace wavebake {

// band 0 = LL (scaling), 1 = detail along x (HL), 2 = detail along y (LH), 3 = HH.
struct Subband {
  int level = 0;
  int band = 0;
  constexpr bool operator==(const Subband&) const = default;
};

// For a depth-d Mallat layout of a W×H image: level 0 is the coarsest (the LL
// block AND the details produced by step d−1 are level 0; details of step s
// are level d−1−s). This is the l of the 2^l scaling in the quantizer. For
// d == 0 everything is {0, 0}.
Subband SubbandAt(int x, int y, int width, int height, int depth);

// ‖synthesis basis function‖₂ of every coefficient of a depth-d transform of a
// W×H image under filter f, as a row-major W×H image of weights: the factor in
// DESIGN.md §1's ranking |c|·‖synthesis basis of its subband‖. 1 everywhere
// for the orthonormal filters (Haar, periodic Daubechies-4). For the
// biorthogonal ones, each subband's value is measured by inverse-transforming a
// unit impulse at the centre of that subband (away from the symmetric-extension
// boundary, so it is the norm of the interior basis functions). Cached per
// (f, W, H, depth); thread-safe.
//
// How far from 1 (tested in tests/core/subband_test.cc, subbands ≥ 8 wide):
// LeGall 5/3 lies in [0.66, 1.44] (first level: LL ¾, HL/LH √(¾·23/16) ≈ 1.04,
// HH 23/16; LL tends to ⅔ with depth); CDF 9/7 in [0.96, 1.08]. Subbands only
// a few coefficients wide have no interior: their centre basis function is
// folded by the symmetric extension and its norm is what it is (e.g. 9/7 LL of
// a 128² image at depth 6: 1.74).
std::vector<float> SynthesisNorms(WaveletFilter f, int width, int height, int depth);
// The same cached weights without a copy; the reference stays valid for the
// life of the process.
const std::vector<float>& SynthesisNormsRef(WaveletFilter f, int width, int height, int depth);

// Row-transform level of a light index inside an N×N face in full-depth Haar
// Mallat layout: 0 for the scaling coefficient (0,0), else
// 1 + floor(log2(max(x,y))). (For the "depth by row level" statistics.)
int RowLevel(int x, int y);

}  // namespace wavebake
