#include "core/products/tripling.h"

#include <algorithm>
#include <array>

#include "core/products/haar_tree.h"

namespace wavebake::haar {
namespace {

bool SameWavelet(const Position& p, const Position& q) {
  return !p.scaling && !q.scaling && p.level == q.level && p.type == q.type && p.sx == q.sx &&
         p.sy == q.sy;
}

// Case 3: `fine` is the repeated wavelet, `third` the scaling function or a
// coarser wavelet.
double RepeatedWavelet(int n, const Position& fine, const Position& third) {
  if (third.scaling) return 1.0 / n;
  const int shift = fine.level - third.level;
  if (shift <= 0) return 0;  // the third must be strictly coarser
  if ((fine.sx >> shift) != third.sx || (fine.sy >> shift) != third.sy) return 0;
  const int q = ((fine.sx >> (shift - 1)) & 1) | (((fine.sy >> (shift - 1)) & 1) << 1);
  return QuadrantSign(third.type, q) * static_cast<double>(1 << third.level) / n;
}

}  // namespace

double TriplingCoefficient(int n, int a, int b, int c) {
  const std::array<Position, 3> p = {Decode(a % n, a / n), Decode(b % n, b / n),
                                     Decode(c % n, c / n)};
  if (p[0].scaling && p[1].scaling && p[2].scaling) return 1.0 / n;
  // Case 2: one square, three different types.
  if (!p[0].scaling && !p[1].scaling && !p[2].scaling && p[0].level == p[1].level &&
      p[1].level == p[2].level && p[0].sx == p[1].sx && p[1].sx == p[2].sx && p[0].sy == p[1].sy &&
      p[1].sy == p[2].sy && p[0].type != p[1].type && p[1].type != p[2].type &&
      p[0].type != p[2].type) {
    return static_cast<double>(1 << p[0].level) / n;
  }
  // Case 3: a repeated wavelet and a third, coarser or scaling, function.
  if (SameWavelet(p[0], p[1])) return RepeatedWavelet(n, p[0], p[2]);
  if (SameWavelet(p[0], p[2])) return RepeatedWavelet(n, p[0], p[1]);
  if (SameWavelet(p[1], p[2])) return RepeatedWavelet(n, p[1], p[0]);
  return 0;
}

}  // namespace wavebake::haar
