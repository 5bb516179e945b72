#pragma once
// Adaptive depth by coded size (DESIGN.md §1 "Column transform"). The depth
// search (core/columns/depth_search.h) finds the depth d* needing the fewest
// coefficients, but a coefficient does not cost the same at every depth: at
// depth 0 the kept cells are runs of neighbouring samples (short index gaps,
// values that repeat), while a deep layout scatters them over subbands with
// larger values. Chosen by count alone, adaptive stores came out larger than
// `--column-mode 2d` at low targets (the bunny, hilbert 64², N = 32, target
// 0.003: 6.02 MB against 5.83 MB). So d* is set against depth 0 by the size
// both codings would take in the store (core/columns/coded_size.h).
#include <cstdint>
#include <span>

#include "core/columns/column_coding.h"

namespace wavebake {

// Whether this comparison applies: adaptive with a target, uniform level
// scaling, ColumnCodingParams::depth_by_size. With --level-scaling paper a step per
// level makes the estimate below a different one; that mode keeps the count.
bool ComparesCodedSize(const ColumnCodingParams& p);

// Whether depth 0 keeping `flat_kept` of `image` codes in no more bits than
// depth d* keeping `deep_kept` of `deep` (ties: depth 0, the shallower).
// Both are quantized with FINALIZE's step as estimated for this column
// (core/columns/quantization_steps.h): with --bits auto the one matrix-wide
// step for which d*'s count of steps Δ²/12 fills the quantization budget
// (target/2)²·E_ref, the same for both codings; with --bits B each coding's
// max over Q_B. Dither is left out: it moves a code by less than one.
bool DepthZeroCodesSmaller(const ColumnCodingParams& p, double reference_energy,
                           std::span<const float> image, std::span<const uint32_t> flat_kept,
                           std::span<const float> deep, std::span<const uint32_t> deep_kept);

}  // namespace wavebake
