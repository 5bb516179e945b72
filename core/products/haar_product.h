#pragma once
// The projected Haar product W = P(f·g) on the cubemap, by the tree algorithm
// of Vollick & Lessig §§3.4–3.6 (Ng et al. 2004; Sun & Mukherjee 2006):
//
//   W_j = Σ_{i,k} C(i, j, k) f_i g_k         (C: core/products/tripling.h)
//
// so that the triple product Σ C f_i V_j g_k is the dot product ⟨V, W⟩. f is
// an RGB factor shared by many products (the lighting of a frame), g a sparse
// scalar one (a sample's BRDF slice). Per face, with f̂(s), ĝ(s) the parent
// sums — the constant value on square s of all basis functions coarser than
// s, scaling included — Theorem 7's three cases become:
//
//   W_φ       += ⟨f, g⟩ / N                            (case 1, and case 3 with j = φ)
//   W_{s,t}   += f_{s,t} ĝ(s) + g_{s,t} f̂(s)           (case 3, the third coarser)
//   W_{s,t}   += 2^l/N · Σ g_{s,t'} f_{s,t''}            (case 2, {t, t', t''} = {0, 1, 2})
//   W_{a,t}   += f_k g_k · b_{a,t}|_{s_k}  for every coarser square a ⊃ s_k   (case 3, j coarser)
//
// f̂ is computed once per factor for every square (top-down, Theorem 6's
// tree); ĝ only on the squares that carry f's terms and their ancestors,
// top-down again. So a product costs O(|g| · levels + |f on g's faces|):
// linear in the kept terms, no coefficient table. Faces where g has no term
// are skipped: there f·g = 0.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/directions/rgb_cube.h"
#include "core/products/haar_tree.h"

namespace wavebake {

// The shared factor f: dense RGB coefficients rgb[3m + c] of the row basis
// (m = face·N² + y·N + x, Mallat layout per face), its parent sums and the
// square tree of its nonzero wavelet terms.
class HaarFactor {
 public:
  HaarFactor() = default;
  // n: the face edge, a power of two ≥ 2; rgb.size() == 3·6n². Zeros are
  // allowed (they become no terms).
  static HaarFactor FromDense(int n, std::span<const float> rgb);

  int n() const { return n_; }
  std::span<const float> rgb() const { return coeff_; }
  int terms() const { return static_cast<int>(term_index_.size()); }

 private:
  friend class HaarProduct;
  // A square on the path from the face root to one of f's terms, in
  // top-down order (parents first): enough to step ĝ from the parent.
  struct Node {
    int32_t parent = -1;                       // node index, −1 for the face root
    std::array<uint32_t, 3> parent_wavelet{};  // face-local indices of the parent's 3 wavelets
    std::array<float, 3> step{};  // sign_t(quadrant) · 2^l/N of each, l the parent's level
  };
  int n_ = 0, squares_ = 0;
  std::vector<float> coeff_;              // [3M]
  std::vector<uint8_t> nonzero_;          // [M]: coefficient m is not 0 in some channel
  std::vector<float> parent_sum_;         // f̂, [3 · 6 · squares]
  std::vector<Node> nodes_;               // all faces, face-major
  std::array<uint32_t, 7> node_start_{};  // per face
  std::vector<uint32_t> term_index_;      // global m of each wavelet term, face-major
  std::vector<uint32_t> term_node_;       // node of the term's square
  std::array<uint32_t, 7> term_start_{};  // per face
};

// The product's scratch (dense g of one face, ĝ on f's tree), reusable
// across products; one per thread.
class HaarProduct {
 public:
  explicit HaarProduct(int n);

  // w += P(f·g), marking the faces it writes. g: sparse scalar terms,
  // indices strictly increasing and < 6n²; f and w made for the same n
  // (checked: a mismatch aborts).
  void Accumulate(const HaarFactor& f, std::span<const uint32_t> g_index,
                  std::span<const float> g_value, RgbCube& w);

  // Only the coefficients W_j at `wanted` (global indices, increasing, all
  // on `face`) into rgb_out[3·t + c] for wanted[t]: what a sparse row dotted
  // with W needs (runtime/relight/sample_rows.h). g_index/g_value: g's terms on that
  // face (increasing). Per wanted j = (s, t) the cases above are read off
  // directly:
  //
  //   W_j = ĝ(s) f_j + g_j f̂(s) + 2^l/N (g_{s,t'} f_{s,t''} + g_{s,t''} f_{s,t'})
  //         + 2^l/N Σ_q sign_t(q) S(child_q(s))
  //
  // with S(c) = Σ f_k g_k over the common terms at or below square c, which
  // each common term adds to its ancestors once. The g-side numbers of the
  // first line (ĝ(s), g_j and the two others) depend on g and j alone: Gather
  // computes them, Combine adds the f side, and a caller whose g and wanted
  // sets stay fixed over many f (a sample's BRDF slice and row, over frames)
  // gathers once. Cost: Gather O(|g| + |wanted| · levels), Combine
  // O(|g| + |f ∩ g| · levels + |wanted|).
  struct Gathered {
    float g_hat = 0, g = 0, g_other[2] = {0, 0};
  };
  void Gather(int face, std::span<const uint32_t> g_index, std::span<const float> g_value,
              std::span<const uint32_t> wanted, std::span<Gathered> out);
  void Combine(const HaarFactor& f, int face, std::span<const uint32_t> g_index,
               std::span<const float> g_value, std::span<const uint32_t> wanted,
               std::span<const Gathered> gathered, std::span<float> rgb_out);
  // Gather + Combine.
  void AtTerms(const HaarFactor& f, int face, std::span<const uint32_t> g_index,
               std::span<const float> g_value, std::span<const uint32_t> wanted,
               std::span<float> rgb_out);

 private:
  void AccumulateFace(const HaarFactor& f, int face, std::span<const uint32_t> g_index,
                      std::span<const float> g_value, RgbCube& w);
  int n_ = 0;
  std::vector<float> g_;      // dense g of the face being processed, [N²]
  std::vector<float> g_hat_;  // ĝ per node of f's tree
  haar::FaceTables tables_;
  // AtTerms: per square, Σ f_k g_k (RGB) of the common terms at it or below,
  // valid where stamp_ == epoch_ (so nothing is cleared between products).
  std::vector<float> subtree_;
  std::vector<uint32_t> stamp_;
  uint32_t epoch_ = 0;
  std::vector<Gathered> gathered_;  // AtTerms
};

}  // namespace wavebake
