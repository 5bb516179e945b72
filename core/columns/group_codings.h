#pragma once
// Adaptive by coded size (docs/PIPELINE.md "§1 Column transform"). DESIGN.md
// §1's adaptive keeps the depth with the fewest coefficients, but fewest is
// not smallest: at depth 0 the kept cells come in runs of neighbours (short
// index deltas, values that repeat) and cost fewer bits each than the
// coefficients of a deep layout. By count alone, adaptive stores came out
// larger than `--column-mode 2d` at low targets (the bunny, hilbert 64²,
// N = 32: 6.02 against 5.83 MB at target 0.003).
//
// So each column of a group also has its depth-0 coding (CodeColumn's
// `flat`), and the group keeps whichever of three choices its arrays take
// the fewest bytes for: every column's fewest-coefficient coding (ties go
// here), each column's cheaper one by the order-0 estimate of
// core/columns/coded_size.h, or every column's depth-0 coding. The bytes are
// the store's own codecs on the group's positions and codes (`bytes`,
// supplied by storage): a per-column estimate alone ranks codings well on
// some scenes and badly on others (spot, N = 64: +1 % against by count),
// while the group choice cannot be larger than by count, nor than depth 0,
// by its own measure.
#include <cstdint>
#include <span>
#include <vector>

#include "core/columns/column_coding.h"

namespace wavebake {

// The bytes that `positions` (columns concatenated, each increasing) and
// their int16 `codes` take in the store's transport arrays.
using CodedBytesFn = size_t (*)(std::span<const uint32_t> positions,
                                std::span<const int16_t> codes);

struct ColumnCodings {
  CodedColumn fewest;  // CodeColumn's coding (DESIGN.md §1's adaptive)
  CodedColumn flat;    // its depth-0 coding; depth < 0: none (the same as `fewest`)
};

// Whether a job compares codings by size: adaptive with a target and
// --level-scaling uniform (a step per level would need its own estimate).
bool ComparesCodedSize(const ColumnCodingParams& p);

// Per column of the group (matrix columns first_column, first_column + 1,
// …), 1 to keep `flat`, 0 to keep `fewest`. Values are quantized as FINALIZE
// would, dither included, with its step as estimated for the group
// (core/columns/quantization_steps.h): with --bits auto the Δ of
// K̄·Δ²/12 = (target/2)²·E_ref, K̄ the group's mean count under the choice
// measured (scope column: the coding's own count); with --bits B each
// coding's max over Q_B.
std::vector<uint8_t> ChooseGroupCodings(const ColumnCodingParams& p,
                                        std::span<const ColumnCodings> group, int first_column,
                                        CodedBytesFn bytes);

}  // namespace wavebake
