#pragma once
// What coded columns add to the store's transport arrays (DESIGN.md §3):
// positions delta-coded and byte-shuffled into transport/indices, int16
// codes into transport/data, each zstd-compressed. Adaptive by coded size
// compares a group's codings by it (core/columns/group_codings.h); core
// knows no codec, so the worker hands it this function. Level 1 rather
// than the store's 9 and 5: a ranking, at a fraction of the time (the
// bunny's N = 64 indices: 73 against 593 ms, docs/RESULTS.md).
#include <cstddef>
#include <cstdint>
#include <span>

namespace wavebake {

size_t TransportBytes(std::span<const uint32_t> positions, std::span<const int16_t> codes);

}  // namespace wavebake
