// HaarProduct::Gather / Combine / AtTerms: W = P(f·g) at chosen
// coefficients only (core/products/haar_product.h).
#include <algorithm>

#include "core/products/haar_product.h"
#include "core/products/haar_product_util.h"
#include "core/util/check_or_die.h"

namespace wavebake {

void HaarProduct::Gather(int face, std::span<const uint32_t> g_index,
                         std::span<const float> g_value, std::span<const uint32_t> wanted,
                         std::span<Gathered> out) {
  CheckOrDie("HaarProduct", out.size() == wanted.size(), "one gathered entry per wanted term");
  const haar::FaceTables& tab = tables_;
  const uint32_t base = static_cast<uint32_t>(face) * n_ * n_;
  for (size_t k = 0; k < g_index.size(); ++k) g_[g_index[k] - base] = g_value[k];
  for (size_t w = 0; w < wanted.size(); ++w) {
    Gathered& o = out[w];
    const uint32_t p = wanted[w] - base;
    o = Gathered{};
    if (p == 0) continue;  // W_φ = ⟨f, g⟩ / N: no g-side number
    const haar::FaceTables::Term& term = tab.term[p];
    o.g = g_[p];
    o.g_other[0] = g_[term.other[0]];
    o.g_other[1] = g_[term.other[1]];
    // ĝ(s): the scaling function's share, then each ancestor's wavelets on
    // the quadrant holding s.
    float ghat = g_[0] / n_;
    for (int32_t s = term.square; tab.square[s].parent >= 0; s = tab.square[s].parent) {
      const haar::FaceTables::Square& parent = tab.square[tab.square[s].parent];
      const float a = tab.amplitude[parent.level];
      const int q = tab.square[s].quadrant;
      for (int t = 0; t < 3; ++t) ghat += haar::QuadrantSign(t, q) * a * g_[parent.wavelet[t]];
    }
    o.g_hat = ghat;
  }
  for (size_t k = 0; k < g_index.size(); ++k) g_[g_index[k] - base] = 0;
}

void HaarProduct::Combine(const HaarFactor& f, int face, std::span<const uint32_t> g_index,
                          std::span<const float> g_value, std::span<const uint32_t> wanted,
                          std::span<const Gathered> gathered, std::span<float> rgb_out) {
  CheckOrDie("HaarProduct", f.n() == n_, "factor made for another face edge");
  CheckOrDie("HaarProduct", rgb_out.size() == 3 * wanted.size() && gathered.size() == wanted.size(),
             "output is not 3 floats and one gathered entry per wanted term");
  const haar::FaceTables& tab = tables_;
  const uint32_t base = static_cast<uint32_t>(face) * n_ * n_;
  const float* fc = f.coeff_.data() + 3 * static_cast<size_t>(base);
  const uint8_t* fnz = f.nonzero_.data() + base;
  const float* fhat = f.parent_sum_.data() + 3 * static_cast<size_t>(face) * f.squares_;
  if (++epoch_ == 0) {  // wrapped: every stamp is stale again
    std::fill(stamp_.begin(), stamp_.end(), 0);
    epoch_ = 1;
  }
  // ⟨f, g⟩ and the common terms' subtree sums.
  float dot[3] = {0, 0, 0};
  for (size_t k = 0; k < g_index.size(); ++k) {
    const uint32_t p = g_index[k] - base;
    if (!fnz[p]) continue;
    const float v = g_value[k];
    const float* fp = fc + 3 * p;
    const float prod[3] = {fp[0] * v, fp[1] * v, fp[2] * v};
    for (int c = 0; c < 3; ++c) dot[c] += prod[c];
    if (p == 0) continue;
    for (int32_t s = tab.term[p].square; s >= 0; s = tab.square[s].parent) {
      float* sum = subtree_.data() + 3 * static_cast<size_t>(s);
      if (stamp_[s] != epoch_) {
        stamp_[s] = epoch_;
        sum[0] = sum[1] = sum[2] = 0;
      }
      for (int c = 0; c < 3; ++c) sum[c] += prod[c];
    }
  }

  const float inv_n = 1.0f / n_;
  for (size_t w = 0; w < wanted.size(); ++w) {
    float* out = rgb_out.data() + 3 * w;
    const uint32_t p = wanted[w] - base;
    if (p == 0) {
      for (int c = 0; c < 3; ++c) out[c] = dot[c] * inv_n;
      continue;
    }
    const Gathered& g = gathered[w];
    const haar::FaceTables::Term& term = tab.term[p];
    const float amp = tab.amplitude[term.level];
    out[0] = out[1] = out[2] = 0;
    if (g.g != 0) {
      const float* fh = fhat + 3 * term.square;
      for (int c = 0; c < 3; ++c) out[c] = g.g * fh[c];
    }
    if (fnz[p]) {
      const float* fj = fc + 3 * p;
      for (int c = 0; c < 3; ++c) out[c] += g.g_hat * fj[c];
    }
    if (g.g_other[0] != 0 || g.g_other[1] != 0) {
      const float* f1 = fc + 3 * term.other[0];
      const float* f2 = fc + 3 * term.other[1];
      for (int c = 0; c < 3; ++c) out[c] += amp * (g.g_other[0] * f2[c] + g.g_other[1] * f1[c]);
    }
    // The common terms below s, by the quadrant they lie in (none if s's own
    // subtree sum was never written).
    const haar::FaceTables::Square& sq = tab.square[term.square];
    if (sq.child < 0 || stamp_[term.square] != epoch_) continue;
    for (int q = 0; q < 4; ++q) {
      const int32_t child = sq.child + (q & 1) + (q >> 1) * sq.child_row;
      if (stamp_[child] != epoch_) continue;
      const float a = amp * haar::QuadrantSign(term.type, q);
      const float* sum = subtree_.data() + 3 * static_cast<size_t>(child);
      for (int c = 0; c < 3; ++c) out[c] += a * sum[c];
    }
  }
}

void HaarProduct::AtTerms(const HaarFactor& f, int face, std::span<const uint32_t> g_index,
                          std::span<const float> g_value, std::span<const uint32_t> wanted,
                          std::span<float> rgb_out) {
  gathered_.resize(wanted.size());
  Gather(face, g_index, g_value, wanted, gathered_);
  Combine(f, face, g_index, g_value, wanted, gathered_, rgb_out);
}

}  // namespace wavebake
