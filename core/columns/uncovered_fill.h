#pragma once
// Values for the cells of a W×H sample grid that no sample covers (−1 in
// samples/grid). Nothing reads them back — the runtime masks them — so a fill
// is free to choose whatever makes the image cheapest to code: zeros leave a
// step at every chart border, which the column wavelets pay for at every
// level; a smooth extension of the chart across the border does not
// (docs/RESULTS.md chart 7 measures both). The same nearest-texel dilation
// widens a lightmap's charts into gutters, so bilinear sampling near a chart
// border never reads the background.
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/layouts/layout.h"

namespace wavebake {

class CellFiller {
 public:
  // grid: [H*W] sample id or −1, row-major; W, H powers of two. kDilate fills
  // cells up to `max_distance` (Chebyshev, in cells) from a covered one.
  CellFiller(UncoveredFill kind, std::span<const int32_t> grid, int width, int height,
             int max_distance = std::numeric_limits<int>::max());

  // Fills the uncovered cells of values[cell*channels + c] in place; covered
  // cells are left as they are.
  //  kZero: 0.
  //  kPushPull: pull — a block's value is the mean of the values of its
  //    children blocks that hold a covered cell (the cells themselves at the
  //    finest level), level by level up to the whole grid; push — from the
  //    coarsest level down, a block without coverage takes its parent's
  //    value. Each Haar step then sees a block's uncovered children equal to
  //    the mean of its covered ones, the fill that minimizes that step's
  //    detail energy, and blocks without coverage have details exactly 0.
  //  kDilate: the value of a nearest covered cell (Chebyshev distance; each
  //    cell copies a neighbour one step closer, the first in the order
  //    N, S, W, E, NW, NE, SW, SE); cells beyond max_distance are untouched.
  void Fill(std::span<float> values, int channels = 1) const;

  // Zeroes every coefficient of a depth-`depth` Haar Mallat layout whose
  // support holds no covered cell: a Haar basis function only reaches its
  // own dyadic block, so dropping those changes no covered cell. (After
  // kPushPull only scaling coefficients can be such and nonzero.)
  void ZeroUncoveredCoefficients(std::span<float> layout, int depth) const;

  UncoveredFill kind() const { return kind_; }

 private:
  void PushPull(std::span<float> values, int channels) const;

  UncoveredFill kind_;
  int width_;
  std::vector<uint8_t> covered_;  // [cells]
  // Children blocks with coverage per block, level by level (level 0 =
  // cells: 1 if covered); sizes_ are BlockExtent(W, l) × BlockExtent(H, l).
  std::vector<std::vector<uint32_t>> counts_;
  std::vector<std::pair<int, int>> sizes_;  // W, H of each level
  // kDilate: (destination, source) cells in the order they must be copied.
  std::vector<std::pair<uint32_t, uint32_t>> copies_;
};

}  // namespace wavebake
