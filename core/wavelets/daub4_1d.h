#pragma once
// Orthonormal Daubechies-4 step with PERIODIC boundary handling (DESIGN.md §1
// "Daubechies-4 is an optional alternative row filter"; 4D paper §4.1).
// Periodization keeps the analysis matrix exactly orthogonal for every even
// length, including 2 (where it folds into Haar), so energy and dot products
// are preserved and the inverse is the transpose. Symmetric extension would
// break orthogonality for an orthonormal non-symmetric filter.
#include <span>

namespace wavebake {

// line: even length n (or 1: untouched); output [lo | hi]; scratch ≥ n floats.
void Daub4Forward1d(std::span<float> line, std::span<float> scratch);
void Daub4Inverse1d(std::span<float> line, std::span<float> scratch);

// The same step along y for columns 0..bw−1 of rows 0..bh−1 of a row-major
// image, each row acting as one sample (unit-stride, vectorizable loops).
void Daub4ForwardRows(std::span<float> img, int width, int bw, int bh);
void Daub4InverseRows(std::span<float> img, int width, int bw, int bh);

}  // namespace wavebake
