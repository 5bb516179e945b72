#pragma once
// Haar tripling coefficients (Vollick & Lessig §3.4–3.6, Theorem 7; Ng et al.
// 2004) for the row basis of one cube face (core/products/haar_tree.h):
//
//   C(a, b, c) = Σ_texels b_a · b_b · b_c
//
// the triple product of three basis functions, summed over the N×N texels of
// the face (the discrete orthonormal basis: every value is the continuous
// coefficient of the unit square divided by N). Nonzero only when
//   1. all three are the scaling function:                       1/N
//   2. all three are wavelets of one square, of the three types:  2^l/N
//   3. two are the same wavelet and the third is the scaling
//      function (1/N) or a wavelet of a strictly coarser square
//      containing it: ± 2^l'/N, l' the coarser level, the sign that
//      of the coarser wavelet on the quadrant holding the finer square.
// Basis functions of different faces never overlap: C = 0.
//
// Only for tests and documentation: the tree algorithm (core/products/haar_product.h)
// never enumerates coefficients, it walks parent sums.
namespace wavebake::haar {

// a, b, c: face-local indices y·N + x in Mallat layout of an N×N face.
double TriplingCoefficient(int n, int a, int b, int c);

}  // namespace wavebake::haar
