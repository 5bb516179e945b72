#include "runtime/gpu/tree_stream.h"

#include "core/products/haar_tree.h"

namespace wavebake {
namespace {

// Child k of square (level, sx, sy), k in line order.
int ChildId(int level, int sx, int sy, int k) {
  return haar::SquareId(level + 1, 2 * sx + (k & 1), 2 * sy + (k >> 1));
}

int Emit(int n, std::span<const uint8_t> kept, int level, int sx, int sy,
         std::vector<TreeNode>& out) {
  const size_t at = out.size();
  out.push_back({.square = haar::SquareId(level, sx, sy), .level = level, .sx = sx, .sy = sy});
  if (level + 1 >= haar::LevelsOf(n)) return 1;
  uint8_t mask = 0;
  int below = 0;
  for (int k = 0; k < 4; ++k) {
    if (!kept[ChildId(level, sx, sy, k)]) continue;
    mask |= uint8_t(1u << k);
    below += Emit(n, kept, level + 1, 2 * sx + (k & 1), 2 * sy + (k >> 1), out);
  }
  out[at].child_mask = mask;
  out[at].descendants = below;
  return 1 + below;
}

}  // namespace

std::vector<uint8_t> KeepLive(int n, std::span<const uint8_t> significant) {
  const int levels = haar::LevelsOf(n);
  std::vector<uint8_t> live(significant.begin(), significant.end());
  for (int l = levels - 2; l >= 0; --l) {  // finest level first: a parent sees its children
    for (int sy = 0; sy < (1 << l); ++sy) {
      for (int sx = 0; sx < (1 << l); ++sx) {
        uint8_t& s = live[haar::SquareId(l, sx, sy)];
        for (int k = 0; k < 4; ++k) s |= live[ChildId(l, sx, sy, k)];
      }
    }
  }
  return live;
}

std::vector<TreeNode> DepthFirstNodes(int n, std::span<const uint8_t> kept) {
  std::vector<TreeNode> out;
  if (kept.empty() || !kept[0]) return out;
  Emit(n, kept, 0, 0, 0, out);
  return out;
}

}  // namespace wavebake
