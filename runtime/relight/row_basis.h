#pragma once
// The lighting side of the row transform (DESIGN.md §1 "Row transform",
// "Relighting"): the same per-face 2D transform the bake applies to every row
// of T, applied to the lighting cubemap, so that B = T·L is one dot product in
// the row basis; and the geometry of its basis functions that the non-linear
// lighting approximation weighs by (Ng et al. 2003 area weighting) and the
// per-band incremental update groups by (Overbeck ch. 6).
#include <span>
#include <vector>

#include "core/bake/bake_params.h"

namespace wavebake {

// In place on an RGB cubemap vector rgb[3*m + c] (m = face*N*N + y*N + x):
// per face and channel, the full-depth Forward2d(filter) of its N×N image,
// Mallat layout, exactly as the bake's row transform (column m of T is the
// coefficient at (x, y) of the transformed face).
void RowTransformCube(WaveletFilter filter, int n, std::span<float> rgb);
// Undoes RowTransformCube (for tests and for lighting-domain diagnostics).
void InverseRowTransformCube(WaveletFilter filter, int n, std::span<float> rgb);

// Per-band grouping of Overbeck §6.1: basis functions of equal support size
// share a band. Band 0 holds the scaling function and the three coarsest
// wavelets (support = the whole face), band b ≥ 1 the wavelets of support
// (N/2^b)² texels, i.e. RowLevel(x, y) − 1. An N-face has log2(N) bands.
int RowBand(int x, int y);
int RowBandCount(int n);

// For every light index m, the solid angle of the nominal support of its
// basis function: the whole face for band 0, else the (N/2^b)-texel square
// block of the face that the Haar wavelet at (x, y) covers. Exact texel
// solid angles (Cubemap::SolidAngle) summed over the block, so the blocks of
// one orientation and level tile the face: they sum to its 4π/6.
// Daubechies-4 wavelets overlap neighbouring blocks; the same nominal block is
// used for them (it ranks them by scale exactly like Haar).
std::vector<float> SupportSolidAngles(int n);

}  // namespace wavebake
