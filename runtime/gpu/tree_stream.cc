#include "runtime/gpu/tree_stream.h"

#include "core/products/haar_tree.h"

namespace wavebake {
namespace {

// Children of square (level, sx, sy), in line order.
int ChildId(int level, int sx, int sy, int k) {
  return haar::SquareId(level + 1, 2 * sx + (k & 1), 2 * sy + (k >> 1));
}

void Emit(int n, std::span<const uint8_t> kept, int level, int sx, int sy,
          std::vector<TreeRecord>& line) {
  const int id = haar::SquareId(level, sx, sy);
  const size_t at = line.size();
  line.push_back({.jump = false, .square = id, .level = level});
  const bool children = level + 1 < haar::LevelsOf(n) && kept[ChildId(level, sx, sy, 0)];
  if (!children) return;
  line.push_back({.jump = true});
  for (int k = 0; k < 4; ++k) Emit(n, kept, level + 1, 2 * sx + (k & 1), 2 * sy + (k >> 1), line);
  line[at + 1].offset = static_cast<int32_t>(line.size() - at);
}

}  // namespace

std::vector<uint8_t> KeepSiblingGroups(int n, std::span<const uint8_t> significant) {
  const int levels = haar::LevelsOf(n);
  // live[s]: s or a descendant is significant; finest level first.
  std::vector<uint8_t> live(significant.begin(), significant.end());
  for (int l = levels - 2; l >= 0; --l) {
    for (int sy = 0; sy < (1 << l); ++sy) {
      for (int sx = 0; sx < (1 << l); ++sx) {
        uint8_t& s = live[haar::SquareId(l, sx, sy)];
        for (int k = 0; k < 4; ++k) s |= live[ChildId(l, sx, sy, k)];
      }
    }
  }
  // §4.4: a group of four siblings is pruned only when all four are.
  std::vector<uint8_t> kept(live.size(), 0);
  kept[0] = live[0];
  for (int l = 0; l + 1 < levels; ++l) {
    for (int sy = 0; sy < (1 << l); ++sy) {
      for (int sx = 0; sx < (1 << l); ++sx) {
        bool any = false;
        for (int k = 0; k < 4; ++k) any |= live[ChildId(l, sx, sy, k)] != 0;
        for (int k = 0; k < 4; ++k) kept[ChildId(l, sx, sy, k)] = any;
      }
    }
  }
  return kept;
}

std::vector<TreeRecord> DepthFirstLine(int n, std::span<const uint8_t> kept) {
  std::vector<TreeRecord> line;
  if (kept.empty() || !kept[0]) return line;
  Emit(n, kept, 0, 0, 0, line);
  // The level codes: a node's next is the record after it, or after its jump.
  auto code_at = [&](size_t i) { return i < line.size() ? line[i].level + 1 : 0; };
  for (size_t i = 0; i < line.size(); ++i) {
    if (line[i].jump) {
      line[i].next_code = code_at(i - 1 + line[i].offset);
    } else {
      const bool has_jump = i + 1 < line.size() && line[i + 1].jump;
      line[i].next_code = code_at(has_jump ? i + 2 : i + 1);
    }
  }
  return line;
}

}  // namespace wavebake
