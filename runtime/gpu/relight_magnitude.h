#pragma once
// The size of Eq. 8's sum (4D paper §4.5) at every cell: what bounds the
// float rounding of any order of evaluating it, so a GPU frame of the 4D
// store (web/static/column_scatter.vert, haar_inverse_step.frag) can be
// compared with the CPU relighter (runtime/relight/relighter.h) within a
// stated bound.
//
// B(p) = Σ_i Σ_k w_i·C_ik·g_k(p), g_k the Haar synthesis function of
// coefficient k at its column's depth: a product of one factor ±1/2 per
// inverse step (the 2D non-standard orthonormal step of
// core/wavelets/haar2d.h). Any evaluation by sums, products with w and
// exact halvings, with at most n roundings on the way from one product to
// the result, is within γ_n · M(p) of the exact B(p) (Higham, Accuracy and
// Stability, §3.1 and §4.2 for a sum tree), where
//   M(p) = Σ_i Σ_k |w_i·C_ik|·|g_k(p)|
// is Eq. 8 evaluated with |·| on every term and every sign of the inverse
// step taken +. This computes M in double.
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/columns/compressed_columns.h"
#include "runtime/relight/lighting.h"

namespace wavebake {

// M per cell and channel, [W·H·3] at 3·(y·W + x) + c, before the albedo.
// Errors: a column filter other than Haar (the only one the GPU mode
// inverts), a light column outside the matrix.
absl::StatusOr<std::vector<float>> RelightMagnitude(const CompressedColumns& columns,
                                                    std::span<const WaveletLight> lights);

}  // namespace wavebake
