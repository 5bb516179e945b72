#include "core/products/haar_tree.h"

#include <cstddef>

namespace wavebake::haar {

FaceTables::FaceTables(int n_) : n(n_), term(static_cast<size_t>(n_) * n_) {
  const int levels = LevelsOf(n);
  square.resize(SquaresOf(n));
  for (int l = 0; l < levels; ++l) amplitude.push_back(static_cast<float>(1 << l) / n);
  for (int p = 1; p < n * n; ++p) {
    const Position pos = Decode(p % n, p / n);
    Term& t = term[p];
    t.square = SquareId(pos.level, pos.sx, pos.sy);
    t.level = static_cast<uint8_t>(pos.level);
    t.type = static_cast<uint8_t>(pos.type);
    t.other[0] = FaceIndex(n, pos.level, (pos.type + 1) % 3, pos.sx, pos.sy);
    t.other[1] = FaceIndex(n, pos.level, (pos.type + 2) % 3, pos.sx, pos.sy);
  }
  for (int l = 0; l < levels; ++l) {
    for (int sy = 0; sy < (1 << l); ++sy) {
      for (int sx = 0; sx < (1 << l); ++sx) {
        Square& s = square[SquareId(l, sx, sy)];
        s.level = static_cast<uint8_t>(l);
        if (l > 0) {
          s.parent = SquareId(l - 1, sx >> 1, sy >> 1);
          s.quadrant = static_cast<uint8_t>(QuadrantInParent(sx, sy));
        }
        for (int t = 0; t < 3; ++t) s.wavelet[t] = FaceIndex(n, l, t, sx, sy);
        if (l + 1 < levels) {
          s.child = SquareId(l + 1, 2 * sx, 2 * sy);
          s.child_row = 1 << (l + 1);
        }
      }
    }
  }
}

}  // namespace wavebake::haar
