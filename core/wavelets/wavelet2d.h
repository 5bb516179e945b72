#pragma once
// One entry point for every 2D wavelet filter, switched by enum
// (DESIGN.md §1 "Row transform", "Column transform"; 4D paper §4.2, Eq. 5–8).
// Images are row-major W×H floats, W and H powers of two (they may differ).
// Step s transforms the top-left (W>>s)×(H>>s) block along rows then columns
// into the Mallat layout [LL HL; LH HH]; block dimensions of length 1 are left
// untouched. Boundary handling: Haar needs none; Daubechies-4 is periodic
// (exactly orthonormal, core/wavelets/daub4_1d.h); LeGall 5/3 and CDF 9/7 use lifting
// with whole-sample symmetric extension (core/wavelets/lifting1d.h). All filters are
// normalized to DC/Nyquist gain √2 per 1D step (core/wavelets/wavelet1d.h).
#include <span>

#include "core/bake/bake_params.h"

namespace wavebake {

// log2(min(W, H)): the number of steps after which the LL block is one row or
// one column thick.
int MaxDepth(int width, int height);

// Steps 0..depth−1 (0 ≤ depth ≤ MaxDepth), and the inverse in reverse order.
void Forward2d(WaveletFilter f, std::span<float> img, int width, int height, int depth);
void Inverse2d(WaveletFilter f, std::span<float> img, int width, int height, int depth);

// ForwardStep(s) transforms the top-left (W>>s)×(H>>s) block; InverseStep(s)
// undoes exactly it. Inverse2d(d) == InverseStep(d−1), …, InverseStep(0):
// the single-step inverse S'_{l→l+1} of the 4D paper's Eq. 8 relighting.
void ForwardStep(WaveletFilter f, std::span<float> img, int width, int height, int step);
void InverseStep(WaveletFilter f, std::span<float> img, int width, int height, int step);

}  // namespace wavebake
