#pragma once
// FINALIZE (DESIGN.md §2): the groups' coded columns (worker/group_result.h)
// become the store's CSC arrays, samples/* and the manifest (DESIGN.md §3),
// then staging is dropped. Quantization happens here because --bits auto is a
// matrix-wide choice: each group recorded, per column, the fewest bits b whose
// expected subtractive-dither error energy Σ_i (Δ_b·2^−l_i·w_i)²/12, Δ_b =
// scale/Q_b, stays ≤ (target/2)²·E_ref (worker/column_coding.h). FINALIZE
// applies that rule to the whole matrix for the matrix error scope and takes
// the max over columns for the column scope (recorded as attrs "bits",
// "bits_needed", "max_column_bits") and quantizes every column with it.
//
// Memory: one group's coded columns plus O(M) column arrays, never S×M.
// Idempotent: a retry rewrites the same bytes, and a retry after staging was
// dropped finds the finished manifest and succeeds without work.
#include <filesystem>

#include "absl/status/status.h"
#include "worker/bake_context.h"

namespace wavebake {

struct FinalizeOptions {
  bool keep_staging = false;
};

absl::Status Finalize(const BakeContext& ctx, const std::filesystem::path& store,
                      const FinalizeOptions& options);

}  // namespace wavebake
