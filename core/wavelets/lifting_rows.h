#pragma once
// The lifting step of core/wavelets/lifting1d.h applied along y to a whole block at
// once: each image row is one "sample", so every predict/update is a
// unit-stride loop across the row (vectorizable, cache-friendly) instead of a
// strided walk down each column. Same arithmetic, same symmetric extension,
// same [lo rows | hi rows] layout as transforming each column with
// LiftingForward1d.
#include <span>

#include "core/wavelets/lifting1d.h"

namespace wavebake {

// Transforms columns 0..bw−1 of rows 0..bh−1 of a row-major image of the given
// width (bh even, or 1: untouched).
void LiftingForwardRows(const LiftingScheme& scheme, std::span<float> img, int width, int bw,
                        int bh);
void LiftingInverseRows(const LiftingScheme& scheme, std::span<float> img, int width, int bw,
                        int bh);

}  // namespace wavebake
