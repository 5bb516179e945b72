#pragma once
// The size of one coded column in the store's transport arrays (DESIGN.md §3),
// estimated as the order-0 entropy of the bytes zstd sees there: positions
// delta-coded and split into their four byte planes (the `shuffle` filter of
// transport/indices), and the little-endian bytes of the int16 codes
// (transport/data), each set of bytes costing n·H of its own histogram.
//
// Adaptive by coded size (core/columns/group_codings.h) uses it to pick, per
// column, the cheaper of two codings for one of the choices it measures;
// the group's choice is then made on real compressed bytes.
#include <cstdint>
#include <span>

namespace wavebake {

// Estimated bits of `positions` (increasing) and their `codes`.
double CodedBits(std::span<const uint32_t> positions, std::span<const int16_t> codes);

}  // namespace wavebake
