#pragma once
// One analysis / synthesis step of a 1D wavelet on a contiguous line
// (DESIGN.md §1 "Row transform", "Column transform"). A forward step maps a
// line of even length n to [n/2 lowpass | n/2 highpass]; the inverse undoes it
// exactly (up to float rounding). Lines of length 1 are left untouched.
//
// Normalization, shared by all filters: the analysis lowpass has DC gain √2
// and the analysis highpass has Nyquist gain √2, as in an orthonormal filter
// bank. So a constant line c of length n gives lowpass c·√2 and zero
// highpass, and magnitudes are comparable across subbands.
#include <span>

#include "core/bake/bake_params.h"

namespace wavebake {

// scratch must hold at least line.size() floats (callers reuse one buffer).
void Forward1d(WaveletFilter f, std::span<float> line, std::span<float> scratch);
void Inverse1d(WaveletFilter f, std::span<float> line, std::span<float> scratch);

// The orthonormal Haar step: lo = (a+b)/√2, hi = (a−b)/√2 for each pair (a, b).
void HaarForward1d(std::span<float> line, std::span<float> scratch);
void HaarInverse1d(std::span<float> line, std::span<float> scratch);

}  // namespace wavebake
