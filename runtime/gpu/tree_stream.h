#pragma once
// The depth-first line of one face's pruned Haar tree (Boulton §4.4–4.5), the
// structure shared by the exported transfer trees (runtime/gpu/wavelet_tree.h)
// and the environment trees (runtime/gpu/env_trees.h).
//
// A face's row coefficients (Mallat layout, 2D non-standard Haar, DESIGN.md
// §1) form a quad tree of squares (core/products/haar_tree.h): level 0 is the whole
// face, a square of level l has four children of level l + 1, and each
// square carries three wavelets (types 0, 1, 2). Pruning follows §4.4: a
// square is kept when it or a descendant is significant, and the four
// children of a square go together (if one is kept, all four are) — so a
// node present in two trees has the same siblings in both, which is what
// lets §4.5's parallel walk of two trees skip a branch with one jump.
//
// The line (§4.5): kept squares depth-first, children in the order
// (2sx, 2sy), (2sx+1, 2sy), (2sx, 2sy+1), (2sx+1, 2sy+1). Every node
// record carries the level of the node that follows it in the line; a node
// whose children follow is followed by a jump record holding the offset from
// the node to the first record past its subtree and that record's level.
#include <cstdint>
#include <span>
#include <vector>

namespace wavebake {

struct TreeRecord {
  bool jump = false;
  int32_t square = -1;  // node: square id (core/products/haar_tree.h SquareId); jump: −1
  int32_t level = 0;    // node: its level
  // node: level + 1 of the node after it (0: the tree ends there).
  // jump: level + 1 of the node it lands on (0: the tree ends there).
  int32_t next_code = 0;
  int32_t offset = 0;  // jump: records from its node to the landing record
};

// Kept squares of a face of edge n (a power of two ≥ 2) under the sibling
// rule, given which squares are significant on their own: [SquaresOf(n)].
std::vector<uint8_t> KeepSiblingGroups(int n, std::span<const uint8_t> significant);

// The depth-first line of the kept squares (empty when the root is not kept;
// a kept square's parent must be kept).
std::vector<TreeRecord> DepthFirstLine(int n, std::span<const uint8_t> kept);

}  // namespace wavebake
