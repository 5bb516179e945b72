#pragma once
// The Haar basis tree of one cube face (Vollick & Lessig §3.5, Theorem 6): the
// row basis of DESIGN.md §1 — 2D non-standard orthonormal Haar, full depth,
// Mallat layout per N×N face — seen as squares. Level l = 0 is the coarsest
// wavelet level (its one square is the whole face); level l has 2^l × 2^l
// squares of N/2^l texels, each carrying three wavelets:
//
//   type 0 (HL, x-difference) at (2^l + sx, sy):       + on the left half, − on the right
//   type 1 (LH, y-difference) at (sx, 2^l + sy):       + on the top half, − on the bottom
//   type 2 (HH, diagonal)     at (2^l + sx, 2^l + sy): + top-left and bottom-right, − elsewhere
//
// with amplitude 2^l/N (unit norm over the N² texels). The scaling function at
// (0, 0) is 1/N on the whole face. This is exactly what core/wavelets/haar2d.h's steps
// produce (HL = (a−b+c−d)/2 etc. applied recursively to the LL block).
//
// Squares of a face are numbered level by level, row-major inside a level:
// id = (4^l − 1)/3 + sy·2^l + sx, so a face has (N² − 1)/3 of them and a
// parent's id is smaller than its children's.
#include <bit>
#include <cstdint>
#include <vector>

namespace wavebake::haar {

// One coefficient position of a face, decoded.
struct Position {
  bool scaling = false;
  int level = 0, type = 0;  // wavelets only
  int sx = 0, sy = 0;       // square inside its level
};

constexpr int LevelsOf(int n) { return std::bit_width(static_cast<unsigned>(n)) - 1; }
constexpr int SquaresOf(int n) { return (n * n - 1) / 3; }
constexpr int SquareId(int level, int sx, int sy) {
  return ((1 << (2 * level)) - 1) / 3 + (sy << level) + sx;
}

// (x, y) of a face in Mallat layout → level, type and square.
constexpr Position Decode(int x, int y) {
  if (x == 0 && y == 0) return {.scaling = true};
  const int level = std::bit_width(static_cast<unsigned>(x > y ? x : y)) - 1;
  const int half = 1 << level;
  if (y < half) return {.level = level, .type = 0, .sx = x - half, .sy = y};
  if (x < half) return {.level = level, .type = 1, .sx = x, .sy = y - half};
  return {.level = level, .type = 2, .sx = x - half, .sy = y - half};
}

// Inverse of Decode for wavelets: the face-local index y·N + x.
constexpr int FaceIndex(int n, int level, int type, int sx, int sy) {
  const int half = 1 << level;
  const int x = type == 1 ? sx : half + sx;
  const int y = type == 0 ? sy : half + sy;
  return y * n + x;
}

// Sign of wavelet `type` on quadrant q of its square (q bit 0: right half,
// bit 1: bottom half).
constexpr int QuadrantSign(int type, int q) {
  const bool right = q & 1, bottom = q & 2;
  if (type == 0) return right ? -1 : 1;
  if (type == 1) return bottom ? -1 : 1;
  return right == bottom ? 1 : -1;
}

// Quadrant of its parent that square (sx, sy) occupies.
constexpr int QuadrantInParent(int sx, int sy) { return (sx & 1) | ((sy & 1) << 1); }

// Everything above, tabulated for one face edge n, for the product kernels
// (core/products/haar_product.h) that look it up per coefficient.
struct FaceTables {
  explicit FaceTables(int n);

  struct Term {           // per face-local index y·n + x
    int32_t square = -1;  // −1: the scaling function
    uint8_t level = 0, type = 0;
    int32_t other[2] = {0, 0};  // face-local indices of the square's other two types
  };
  struct Square {
    int32_t parent = -1;              // −1: the face root
    uint8_t level = 0, quadrant = 0;  // quadrant of this square in its parent
    int32_t wavelet[3] = {0, 0, 0};   // face-local indices of its three wavelets
    int32_t child = -1;               // id of its top-left child (−1: finest level)
    int32_t child_row = 0;            // + child_row: the children of the next row
  };
  int n = 0;
  std::vector<Term> term;
  std::vector<Square> square;
  std::vector<float> amplitude;  // 2^l / n per level
};

}  // namespace wavebake::haar
