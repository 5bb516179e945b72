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
// `flat`), taken where the order-0 estimate of core/columns/coded_size.h
// says it codes smaller, and the group keeps these choices only if its
// arrays, compressed with the store's own codecs (`bytes`, supplied by
// storage), come out smaller than with every column's fewest-coefficient
// coding (ties: the fewest). The per-column estimate alone made spot
// (N = 64) 1 % larger than by count; a third choice, every column at depth
// 0, won by the group's measure on cubes-wall (camera 64², N = 32) and made
// the store larger, so it is not offered.
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
  CodedColumn fewest;             // CodeColumn's coding (DESIGN.md §1's adaptive)
  CodedColumn flat = NoCoding();  // its depth-0 coding; depth < 0: none
};

// Per column of the group (matrix columns first_column, first_column + 1,
// …), 1 to keep `flat`, 0 to keep `fewest`. Values are quantized as FINALIZE
// would, dither included, with its step as estimated for the group
// (core/columns/quantization_steps.h): with --bits auto the Δ of
// K̄·Δ²/12 = (target/2)²·E_ref, K̄ the group's mean fewest count (scope
// column: the coding's own count), each added coefficient charged the bits
// it costs the shared step; with --bits B each coding's max over Q_B.
std::vector<uint8_t> ChooseGroupCodings(const ColumnCodingParams& p,
                                        std::span<const ColumnCodings> group, int first_column,
                                        CodedBytesFn bytes);

}  // namespace wavebake
