#pragma once
// One step of a separable 2D wavelet transform built from a 1D filter
// (core/wavelets/wavelet1d.h): the top-left (W>>step)×(H>>step) block of a row-major
// W×H image is transformed along rows, then along columns, leaving the Mallat
// layout [LL HL; LH HH] in that block (DESIGN.md §1, non-standard
// decomposition). A block dimension of length 1 is left untouched.
#include <span>

#include "core/bake/bake_params.h"

namespace wavebake {

// Extent of the step-`step` block along a dimension of length n (at least 1).
inline int BlockExtent(int n, int step) { return step < 31 && (n >> step) > 1 ? n >> step : 1; }

void SeparableForwardStep(WaveletFilter f, std::span<float> img, int width, int height, int step);
// Undoes SeparableForwardStep exactly: columns first, then rows.
void SeparableInverseStep(WaveletFilter f, std::span<float> img, int width, int height, int step);

}  // namespace wavebake
