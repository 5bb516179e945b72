// HaarProduct::AtTerms: W = P(f·g) at chosen coefficients only (the cases
// of core/haar_product.h read off per wanted index).
#include <algorithm>

#include "core/haar_product.h"
#include "core/haar_product_util.h"

namespace wavebake {

using haar_product::CheckOrDie;

void HaarProduct::AtTerms(const HaarFactor& f, int face, std::span<const uint32_t> g_index,
                          std::span<const float> g_value, std::span<const uint32_t> wanted,
                          std::span<float> rgb_out) {
  CheckOrDie(f.n() == n_, "factor made for another face edge");
  CheckOrDie(rgb_out.size() == 3 * wanted.size(), "output is not 3 floats per wanted term");
  const haar::FaceTables& tab = tables_;
  const float inv_n = 1.0f / n_;
  const uint32_t base = static_cast<uint32_t>(face) * n_ * n_;
  const float* fc = f.coeff_.data() + 3 * static_cast<size_t>(base);
  const float* fhat = f.parent_sum_.data() + 3 * static_cast<size_t>(face) * f.squares_;
  if (++epoch_ == 0) {  // wrapped: every stamp is stale again
    std::fill(stamp_.begin(), stamp_.end(), 0);
    epoch_ = 1;
  }

  // g dense; ⟨f, g⟩ and the common terms' subtree sums over f's terms on
  // the face (the lighting's are few: fewer than g's).
  for (size_t k = 0; k < g_index.size(); ++k) g_[g_index[k] - base] = g_value[k];
  float dot[3] = {fc[0] * g_[0], fc[1] * g_[0], fc[2] * g_[0]};
  for (uint32_t t = f.term_start_[face]; t < f.term_start_[face + 1]; ++t) {
    const uint32_t p = f.term_index_[t] - base;
    const float v = g_[p];
    if (v == 0) continue;
    const float* fp = fc + 3 * p;
    const float prod[3] = {fp[0] * v, fp[1] * v, fp[2] * v};
    for (int c = 0; c < 3; ++c) dot[c] += prod[c];
    for (int32_t s = tab.term[p].square; s >= 0; s = tab.square[s].parent) {
      float* sum = subtree_.data() + 3 * static_cast<size_t>(s);
      if (stamp_[s] != epoch_) {
        stamp_[s] = epoch_;
        sum[0] = sum[1] = sum[2] = 0;
      }
      for (int c = 0; c < 3; ++c) sum[c] += prod[c];
    }
  }

  for (size_t w = 0; w < wanted.size(); ++w) {
    float* out = rgb_out.data() + 3 * w;
    const uint32_t p = wanted[w] - base;
    if (p == 0) {  // W_φ = ⟨f, g⟩ / N
      for (int c = 0; c < 3; ++c) out[c] = dot[c] * inv_n;
      continue;
    }
    const haar::FaceTables::Term& term = tab.term[p];
    const haar::FaceTables::Square& sq = tab.square[term.square];
    const float amp = tab.amplitude[term.level];
    // Case 3, f's coarser functions: g_j f̂(s).
    const float gj = g_[p];
    const float* fh = fhat + 3 * term.square;
    for (int c = 0; c < 3; ++c) out[c] = gj * fh[c];
    // Case 3, j coarser: the common terms below s, by the quadrant they lie in
    // (none if s's own subtree sum was never written).
    if (sq.child >= 0 && stamp_[term.square] == epoch_) {
      for (int q = 0; q < 4; ++q) {
        const int32_t child = sq.child + (q & 1) + (q >> 1) * sq.child_row;
        if (stamp_[child] != epoch_) continue;
        const float a = amp * haar::QuadrantSign(term.type, q);
        const float* sum = subtree_.data() + 3 * static_cast<size_t>(child);
        for (int c = 0; c < 3; ++c) out[c] += a * sum[c];
      }
    }
    // Case 2: the square's other two types.
    const float g1 = g_[term.other[0]], g2 = g_[term.other[1]];
    if (g1 != 0 || g2 != 0) {
      const float* f1 = fc + 3 * term.other[0];
      const float* f2 = fc + 3 * term.other[1];
      for (int c = 0; c < 3; ++c) out[c] += amp * (g1 * f2[c] + g2 * f1[c]);
    }
    // Case 3, g's coarser functions: f_j ĝ(s), ĝ up the ancestors.
    if (!f.nonzero_[base + p]) continue;
    const float* fj = fc + 3 * p;
    float ghat = g_[0] * inv_n;
    for (int32_t s = term.square; tab.square[s].parent >= 0; s = tab.square[s].parent) {
      const haar::FaceTables::Square& parent = tab.square[tab.square[s].parent];
      const float a = tab.amplitude[parent.level];
      const int q = tab.square[s].quadrant;
      for (int t = 0; t < 3; ++t) ghat += haar::QuadrantSign(t, q) * a * g_[parent.wavelet[t]];
    }
    for (int c = 0; c < 3; ++c) out[c] += fj[c] * ghat;
  }
  for (size_t k = 0; k < g_index.size(); ++k) g_[g_index[k] - base] = 0;
}

}  // namespace wavebake
