#pragma once
// The numcodecs "delta" filter (DESIGN.md §3 welcomes it on transport/indices):
// each chunk, flattened in C order, is stored as its first element followed by
// the differences of neighbours, in the array's own integer type. Arithmetic
// wraps modulo 2^bits exactly as numpy's diff/cumsum do, so any values round
// trip, including the drops where a CSC column's indices restart.
#include <cstddef>
#include <span>

#include "storage/zarr/dtype.h"

namespace wavebake {

// In place over one whole chunk; `dtype` must be an integer type.
void DeltaEncode(DType dtype, std::span<std::byte> chunk);
void DeltaDecode(DType dtype, std::span<std::byte> chunk);

}  // namespace wavebake
