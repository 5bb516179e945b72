#pragma once
// The depth search of a column whose grid has uncovered cells (the uv
// layout, core/columns/uncovered_fill.h): the transform runs on the image with those
// cells filled, and coefficients that only reach uncovered cells are free.
#include <span>

#include "core/columns/column_coding.h"
#include "core/columns/depth_search.h"

namespace wavebake {

// ChooseDepth (core/columns/depth_search.h) for p.filler != null, else ChooseDepth
// itself. Depth 0 codes the cells themselves, where a fill would cost what
// zeros get for free: it is counted on the image as it is. Depths ≥ 1 are
// transformed from the filled image; with Haar, coefficients whose support
// holds no covered cell are zeroed (CellFiller::ZeroUncoveredCoefficients)
// before counting, and every depth is counted exactly (a budget search) —
// the bounds of depth_search.h do not know about free coefficients. The
// energy budget is spent over every cell, filled ones too, so the error over
// the covered cells stays within it.
DepthChoice ChooseFilledDepth(const ColumnCodingParams& p, std::span<const float> image,
                              double budget);

// The column's coefficients at a given depth, as ChooseFilledDepth would
// have them had it chosen `depth`: the image itself at 0; else transformed
// (from the filled image when p.filler is set, free Haar coefficients
// zeroed). No search: an update's recomputed column keeps its old depth
// (worker/columns/local_columns.h).
DepthChoice FilledAtDepth(const ColumnCodingParams& p, std::span<const float> image, int depth);

}  // namespace wavebake
