#pragma once
// The depth-first order of one face's pruned Haar tree (Boulton §4.4–4.5), the
// structure shared by the exported transfer trees (runtime/gpu/wavelet_tree.h)
// and the environment trees (runtime/gpu/env_trees.h).
//
// A face's row coefficients (Mallat layout, 2D non-standard Haar, DESIGN.md
// §1) form a quad tree of squares (core/products/haar_tree.h): level 0 is the
// whole face, a square of level l has four children of level l + 1, and each
// square carries three wavelets (types 0, 1, 2). Pruning: a square is kept
// when it or a descendant is significant (§4.4's rule without its sibling
// groups: §4.4 keeps the four children of a node together so that the GPU
// can index them, which at the cut-offs that matter fills 30 % of the kept
// nodes with siblings nothing needs). Each node instead records which of
// its four children follow (a child mask), so a parallel walk of two trees
// (§4.5, Eq. 3) knows at every node which children both trees hold.
//
// The order (§4.5): kept squares depth-first, children in the order
// k = 0..3: (2sx, 2sy), (2sx+1, 2sy), (2sx, 2sy+1), (2sx+1, 2sy+1).
#include <cstdint>
#include <span>
#include <vector>

namespace wavebake {

struct TreeNode {
  int32_t square = 0;  // core/products/haar_tree.h SquareId
  int32_t level = 0, sx = 0, sy = 0;
  uint8_t child_mask = 0;   // bit k: child k is kept (and follows in the order)
  int32_t descendants = 0;  // kept nodes below this one
};

// Squares of a face of edge n (a power of two ≥ 2) that are significant or
// have a significant descendant, given which are significant: [SquaresOf(n)].
std::vector<uint8_t> KeepLive(int n, std::span<const uint8_t> significant);

// The kept squares in depth-first order (empty when the root is not kept; a
// kept square's parent must be kept).
std::vector<TreeNode> DepthFirstNodes(int n, std::span<const uint8_t> kept);

}  // namespace wavebake
