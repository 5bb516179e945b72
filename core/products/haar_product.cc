#include "core/products/haar_product.h"

#include <algorithm>

#include "core/products/haar_product_util.h"
#include "core/products/haar_tree.h"
#include "core/util/check_or_die.h"
#include "core/util/power_of_two.h"

namespace wavebake {
namespace {

using haar_product::NonZero;

// f̂ on every square of one face, top-down: the root gets the scaling
// function's 1/N share, each child its parent's value plus the parent's three
// wavelets on the child's quadrant.
void FaceParentSums(int n, const float* face_rgb, float* out) {
  const int levels = haar::LevelsOf(n);
  if (levels == 0) return;
  for (int c = 0; c < 3; ++c) out[c] = face_rgb[c] / n;
  for (int l = 1; l < levels; ++l) {
    const float amp = static_cast<float>(1 << (l - 1)) / n;
    for (int sy = 0; sy < (1 << l); ++sy) {
      for (int sx = 0; sx < (1 << l); ++sx) {
        const int px = sx >> 1, py = sy >> 1, q = haar::QuadrantInParent(sx, sy);
        const float* parent = out + 3 * haar::SquareId(l - 1, px, py);
        float* self = out + 3 * haar::SquareId(l, sx, sy);
        for (int c = 0; c < 3; ++c) self[c] = parent[c];
        for (int t = 0; t < 3; ++t) {
          const float s = haar::QuadrantSign(t, q) * amp;
          const float* w = face_rgb + 3 * haar::FaceIndex(n, l - 1, t, px, py);
          for (int c = 0; c < 3; ++c) self[c] += s * w[c];
        }
      }
    }
  }
}

}  // namespace

HaarFactor HaarFactor::FromDense(int n, std::span<const float> rgb) {
  CheckOrDie("HaarProduct", IsPowerOfTwo(n), "face edge is not a power of two");
  CheckOrDie("HaarProduct", rgb.size() == static_cast<size_t>(18) * n * n,
             "factor is not 3·6N² floats");
  HaarFactor f;
  f.n_ = n;
  f.squares_ = haar::SquaresOf(n);
  f.coeff_.assign(rgb.begin(), rgb.end());
  f.nonzero_.resize(rgb.size() / 3);
  for (size_t m = 0; m < f.nonzero_.size(); ++m) f.nonzero_[m] = NonZero(&rgb[3 * m]);
  f.parent_sum_.assign(static_cast<size_t>(3) * 6 * f.squares_, 0.0f);
  const size_t per_face = static_cast<size_t>(n) * n;
  std::vector<int32_t> node_of(f.squares_);
  for (int face = 0; face < 6; ++face) {
    const float* face_rgb = f.coeff_.data() + 3 * face * per_face;
    FaceParentSums(n, face_rgb, f.parent_sum_.data() + 3 * static_cast<size_t>(face) * f.squares_);
    // Mark the squares of the face's wavelet terms and their ancestors.
    std::vector<uint8_t> needed(f.squares_, 0);
    std::vector<std::pair<uint32_t, int32_t>> terms;  // (face-local index, square)
    for (size_t p = 1; p < per_face; ++p) {
      if (!NonZero(face_rgb + 3 * p)) continue;
      const haar::Position pos = haar::Decode(static_cast<int>(p % n), static_cast<int>(p / n));
      terms.push_back({static_cast<uint32_t>(p), haar::SquareId(pos.level, pos.sx, pos.sy)});
      for (int l = pos.level, sx = pos.sx, sy = pos.sy; l >= 0; --l, sx >>= 1, sy >>= 1) {
        uint8_t& mark = needed[haar::SquareId(l, sx, sy)];
        if (mark) break;
        mark = 1;
      }
    }
    f.node_start_[face] = static_cast<uint32_t>(f.nodes_.size());
    f.term_start_[face] = static_cast<uint32_t>(f.term_index_.size());
    std::fill(node_of.begin(), node_of.end(), -1);
    const int levels = haar::LevelsOf(n);
    for (int l = 0; l < levels; ++l) {  // square ids grow level by level: parents first
      for (int sy = 0; sy < (1 << l); ++sy) {
        for (int sx = 0; sx < (1 << l); ++sx) {
          const int id = haar::SquareId(l, sx, sy);
          if (!needed[id]) continue;
          Node node;
          if (l > 0) {
            const int px = sx >> 1, py = sy >> 1, q = haar::QuadrantInParent(sx, sy);
            node.parent = node_of[haar::SquareId(l - 1, px, py)];
            for (int t = 0; t < 3; ++t) {
              node.parent_wavelet[t] = static_cast<uint32_t>(haar::FaceIndex(n, l - 1, t, px, py));
              node.step[t] = haar::QuadrantSign(t, q) * static_cast<float>(1 << (l - 1)) / n;
            }
          }
          node_of[id] = static_cast<int32_t>(f.nodes_.size());
          f.nodes_.push_back(node);
        }
      }
    }
    for (const auto& [p, square] : terms) {
      f.term_index_.push_back(static_cast<uint32_t>(face * per_face + p));
      f.term_node_.push_back(static_cast<uint32_t>(node_of[square]));
    }
  }
  f.node_start_[6] = static_cast<uint32_t>(f.nodes_.size());
  f.term_start_[6] = static_cast<uint32_t>(f.term_index_.size());
  return f;
}

HaarProduct::HaarProduct(int n)
    : n_(n),
      g_(static_cast<size_t>(n) * n, 0.0f),
      tables_(n),
      subtree_(3 * tables_.square.size(), 0.0f),
      stamp_(tables_.square.size(), 0) {}

void HaarProduct::Accumulate(const HaarFactor& f, std::span<const uint32_t> g_index,
                             std::span<const float> g_value, RgbCube& w) {
  CheckOrDie("HaarProduct", f.n() == n_ && w.n == n_,
             "factor or output made for another face edge");
  CheckOrDie("HaarProduct", g_index.size() == g_value.size(), "g index and value sizes differ");
  const uint32_t per_face = static_cast<uint32_t>(n_) * n_;
  size_t first = 0;
  while (first < g_index.size()) {
    const uint32_t face = g_index[first] / per_face;
    CheckOrDie("HaarProduct", face < 6, "g index outside the cube");
    size_t last = first + 1;
    while (last < g_index.size() && g_index[last] / per_face == face) {
      CheckOrDie("HaarProduct", g_index[last] > g_index[last - 1], "g indices are not increasing");
      ++last;
    }
    AccumulateFace(f, static_cast<int>(face), g_index.subspan(first, last - first),
                   g_value.subspan(first, last - first), w);
    first = last;
  }
}

void HaarProduct::AccumulateFace(const HaarFactor& f, int face, std::span<const uint32_t> g_index,
                                 std::span<const float> g_value, RgbCube& out) {
  const int n = n_;
  const uint32_t per_face = static_cast<uint32_t>(n) * n;
  const uint32_t base = static_cast<uint32_t>(face) * per_face;
  const float* fc = f.coeff_.data() + 3 * static_cast<size_t>(base);
  const float* fhat = f.parent_sum_.data() + 3 * static_cast<size_t>(face) * f.squares_;
  float* w = out.face(face);
  for (size_t k = 0; k < g_index.size(); ++k) g_[g_index[k] - base] = g_value[k];

  float dot[3] = {0, 0, 0};
  for (size_t k = 0; k < g_index.size(); ++k) {
    const uint32_t p = g_index[k] - base;
    const float v = g_value[k];
    const float* fp = fc + 3 * p;
    for (int c = 0; c < 3; ++c) dot[c] += fp[c] * v;
    if (p == 0) continue;  // the scaling function: only in ⟨f, g⟩
    const haar::Position pos = haar::Decode(static_cast<int>(p % n), static_cast<int>(p / n));
    const float amp = static_cast<float>(1 << pos.level) / n;
    // Case 3, f's coarser functions: g_{s,t} f̂(s).
    const float* fh = fhat + 3 * haar::SquareId(pos.level, pos.sx, pos.sy);
    for (int c = 0; c < 3; ++c) w[3 * p + c] += v * fh[c];
    // Case 2: g_{s,t} f_{s,t''} lands on the third type t'.
    for (int t = 0; t < 3; ++t) {
      if (t == pos.type) continue;
      const int third = 3 - t - pos.type;
      const float* f3 = fc + 3 * haar::FaceIndex(n, pos.level, third, pos.sx, pos.sy);
      float* wt = w + 3 * haar::FaceIndex(n, pos.level, t, pos.sx, pos.sy);
      for (int c = 0; c < 3; ++c) wt[c] += amp * v * f3[c];
    }
    // Case 3, the repeated wavelet f_k g_k onto every coarser wavelet above it.
    if (!NonZero(fp)) continue;
    const float prod[3] = {fp[0] * v, fp[1] * v, fp[2] * v};
    for (int l = pos.level - 1, sx = pos.sx, sy = pos.sy; l >= 0; --l) {
      const int q = haar::QuadrantInParent(sx, sy);
      sx >>= 1, sy >>= 1;
      const float a = static_cast<float>(1 << l) / n;
      for (int t = 0; t < 3; ++t) {
        const float s = haar::QuadrantSign(t, q) * a;
        float* wt = w + 3 * haar::FaceIndex(n, l, t, sx, sy);
        for (int c = 0; c < 3; ++c) wt[c] += s * prod[c];
      }
    }
  }
  for (int c = 0; c < 3; ++c) w[c] += dot[c] / n;  // W_φ = ⟨f, g⟩ / N

  // Case 3, g's coarser functions: f_{s,t} ĝ(s), ĝ top-down over f's tree.
  const uint32_t first_node = f.node_start_[face], last_node = f.node_start_[face + 1];
  g_hat_.resize(std::max<size_t>(g_hat_.size(), last_node - first_node));
  for (uint32_t k = first_node; k < last_node; ++k) {
    const HaarFactor::Node& node = f.nodes_[k];
    float value;
    if (node.parent < 0) {
      value = g_[0] / n;
    } else {
      value = g_hat_[node.parent - first_node];
      for (int t = 0; t < 3; ++t) value += g_[node.parent_wavelet[t]] * node.step[t];
    }
    g_hat_[k - first_node] = value;
  }
  for (uint32_t t = f.term_start_[face]; t < f.term_start_[face + 1]; ++t) {
    const uint32_t m = f.term_index_[t];
    const float gh = g_hat_[f.term_node_[t] - first_node];
    const float* fm = f.coeff_.data() + 3 * static_cast<size_t>(m);
    float* wm = out.rgb.data() + 3 * static_cast<size_t>(m);
    for (int c = 0; c < 3; ++c) wm[c] += fm[c] * gh;
  }
  for (size_t k = 0; k < g_index.size(); ++k) g_[g_index[k] - base] = 0;
  out.touched[face] = true;
}

}  // namespace wavebake
