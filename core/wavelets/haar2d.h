#pragma once
// 2D non-standard orthonormal Haar transform in place, Mallat layout
// (DESIGN.md §1 "Row transform"; Vollick & Lessig §2 for the basis).
// Step s transforms the top-left (W>>s)×(H>>s) block of a row-major W×H image
// (W, H powers of two): each 2×2 cell [a b; c d] becomes
//   LL = (a+b+c+d)/2   HL = (a−b+c−d)/2   LH = (a+b−c−d)/2   HH = (a−b−c+d)/2
// which equals a 1D step (x+y)/√2, (x−y)/√2 along rows then along columns,
// with LL in the top-left quarter, HL top-right, LH bottom-left, HH
// bottom-right. A block dimension of length 1 gets only the 1D step along the
// other one. This is the per-face row transform (N×N, full depth) and the
// `haar` column filter.
#include <span>

namespace wavebake {

void HaarForwardStep2d(std::span<float> img, int width, int height, int step);
void HaarInverseStep2d(std::span<float> img, int width, int height, int step);

// Steps 0..depth−1, and their inverses in reverse order.
void HaarForward2d(std::span<float> img, int width, int height, int depth);
void HaarInverse2d(std::span<float> img, int width, int height, int depth);

}  // namespace wavebake
