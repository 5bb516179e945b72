#pragma once
// The row transform of the bake (DESIGN.md §1 "Row transform"): each cube
// face of a row of T — the N×N block of texels m = face*N*N + y*N + x — gets
// a full-depth 2D non-standard wavelet transform in place, Mallat layout, so
// the face's scaling coefficient lands at its texel (0, 0). The filters are
// orthonormal, so a relit value T·L is the same dot product in this basis.
#include <span>

#include "core/bake/bake_params.h"

namespace wavebake {

// row: the M = 6 n² entries of one row (n² for a plane light domain: one
// face), n a power of two. row_filter: haar
// (the default) or daub4 (BakeParams::row_filter, checked by
// ValidateBakeParams); any filter of core/wavelets/wavelet2d.h works.
void RowTransform(WaveletFilter row_filter, int n, std::span<float> row);

// Undoes RowTransform exactly (up to float rounding).
void InverseRowTransform(WaveletFilter row_filter, int n, std::span<float> row);

}  // namespace wavebake
