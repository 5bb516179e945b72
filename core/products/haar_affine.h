#pragma once
// Affine coupling coefficients of the 1D Haar basis (Sun & Ramamoorthi 2009,
// §§3.2, 4.2, Appendix D):
//
//   D_ik(s, o) = ∫ Φ_i(s v + o) Φ_k(v) dv                         (Eq. 8)
//
// Φ_i a source function (the light, in its own coordinates q = s v + o),
// Φ_k a target function (the face, coordinates v); s > 0 is the scale, o the
// offset. The functions are the 1D factors of the non-standard 2D Haar basis
// the row transform uses (core/wavelets/wavelet2d.h): on [0, 1], L2-normalized,
//
//   φ_{l,t}(v) = 2^{l/2} φ(2^l v − t),   ψ_{l,t}(v) = 2^{l/2} ψ(2^l v − t),
//
// φ the box on [0, 1), ψ = +1 on [0, ½), −1 on [½, 1) (the sign of the
// row transform's (a − b)/√2 detail). A 2D non-standard basis function at
// level l is a product of two such factors of level l (Eq. 25), so a 2D
// coupling coefficient is a product of two of these (Eq. 26).
//
// Eq. 16–18 reduce D to a canonical coupling coefficient M(r, c) of two
// mother functions, one of them transformed to radius r and centre c. The
// paper gives M for ψ against ψ (Fig. 4); the scaling factors φ of the
// non-standard basis need the same reduction with a box on either side,
// which is an overlap length of intervals.
#include <cstdint>
#include <vector>

namespace wavebake {

// One 1D factor: a scaling function or a wavelet of level l, offset t.
struct Haar1d {
  bool wavelet = false;
  int level = 0;
  int offset = 0;
  bool operator==(const Haar1d&) const = default;
};

// Factors of levels 0..log2(n)−1 of an n-texel axis: φ_{l,t} and ψ_{l,t} for
// t < 2^l, numbered level by level: φ_{l,·} at 2(2^l − 1) + t, ψ_{l,·} right
// after. 2(n − 1) in all.
int Haar1dCount(int n);
int Haar1dId(Haar1d f);
Haar1d Haar1dOf(int id);
// The value of f at v (0 outside [0, 1)); tests integrate with it.
double Haar1dValue(Haar1d f, double v);

// The two 1D factors (x, then y) of the non-standard basis function at Mallat
// position (x, y) of an n×n image: (0,0) is φ_0 ⊗ φ_0; in the level-l
// quadrants x ∈ [2^l, 2^{l+1}) with y < 2^l is ψ ⊗ φ, x < 2^l with
// y ∈ [2^l, 2^{l+1}) is φ ⊗ ψ, both ≥ 2^l is ψ ⊗ ψ (rows are transformed
// before columns, low-pass first).
struct FactorPair {
  Haar1d x, y;
};
FactorPair NonStandardFactors(int x, int y);

// Eq. 17, Fig. 4: M(r, c) = ∫ ψ(u/(2r) − c/(2r) + ½) ψ(u) du, r > 0.
double CanonicalCoupling(double r, double c);
// The same reduction for any pair of mother functions: the transformed one
// (source) and the fixed one (target), each a box φ or a wavelet ψ.
double CanonicalCoupling(bool source_wavelet, bool target_wavelet, double r, double c);

// Eq. 16 with Eq. 18's r and c: D_ik(s, o) = 2^{(l_i − l_k)/2} M(r, c). s > 0.
double AffineCoupling(Haar1d source, Haar1d target, double s, double o);

// One nonzero coupling of a source factor: target factor id and D.
struct Coupling1d {
  uint16_t target;
  float value;
};

// Every nonzero D_ik(s, o) of source factor i against the factors of an
// n-texel target axis, appended to `out` (Appendix D's overlap argument
// gives the candidates: at each target level the scaling functions that
// overlap the image of i's support, and the wavelets whose support contains
// one of its at most three breakpoints — any other wavelet sees a constant
// and integrates it to 0). Exact (Eq. 16 per candidate).
void SourceCouplings(Haar1d source, double s, double o, int n, std::vector<Coupling1d>& out);

}  // namespace wavebake
