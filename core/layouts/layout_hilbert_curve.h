#pragma once
// Hilbert curves: the 2D curve that threads the sample grid and the 3D key
// that orders mesh vertices (DESIGN.md §1 "Spatial layout"). Both keep
// consecutive positions adjacent, which is all the layout needs from them.
#include <cstdint>
#include <vector>

namespace wavebake {

// Cell index y*width + x of each position t along a curve through the whole
// width×height grid (powers of two). A square grid is one Hilbert curve from
// (0,0) to (width−1,0). A wide grid is a row of height×height blocks, each one
// such curve, so block k ends next to where block k+1 starts; a tall grid is
// the same transposed. Consecutive cells are always 4-neighbours.
std::vector<int32_t> HilbertCurveCells(int width, int height);

// Position along the 3D Hilbert curve of the point (x, y, z) of the
// 2^bits-cube, bits in 1..21 (Skilling's transpose, then bit interleaving).
uint64_t HilbertKey3(uint32_t x, uint32_t y, uint32_t z, int bits);

}  // namespace wavebake
