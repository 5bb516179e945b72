#pragma once
// The size of one coded column in the store's transport arrays (DESIGN.md §3),
// estimated as the order-0 entropy of the bytes zstd sees there: positions
// delta-coded and split into their four byte planes (the `shuffle` filter of
// transport/indices), and the little-endian bytes of the int16 codes
// (transport/data), each set of bytes costing n·H of its own histogram.
//
// It ranks two codings of a column as the store's chunks do: choosing each
// column of the bunny (hilbert 64², N = 32) between its depth-0 and its
// fewest-coefficient coding by this estimate gave 5.773 MB at target 0.003
// (by count 5.980, all at depth 0 5.790), 3.696 MB at 0.01 (3.769, 3.762) and
// 1.766 MB at 0.03 (1.768, 2.063), within 0.1 % of choosing by compressing
// each column alone with zstd, at a fraction of its cost.
#include <cstdint>
#include <span>

namespace wavebake {

// Estimated bits of `positions` (increasing) and their `codes`.
double CodedBits(std::span<const uint32_t> positions, std::span<const int16_t> codes);

}  // namespace wavebake
