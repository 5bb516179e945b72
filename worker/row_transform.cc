#include "worker/row_transform.h"

#include <cstdio>
#include <cstdlib>

#include "core/wavelet2d.h"

namespace wavebake {
namespace {

constexpr int kFaces = 6;

// The row's shape is fixed by the job's BakeParams, so a mismatch is a
// programming error, not bad input (as in core/transport_row.cc).
void CheckRowOrDie(int n, std::span<const float> row) {
  if (n > 0 && (n & (n - 1)) == 0 && row.size() == static_cast<size_t>(kFaces) * n * n) return;
  std::fprintf(stderr, "RowTransform: row of %zu entries is not 6·n² for n=%d a power of two\n",
               row.size(), n);
  std::abort();
}

std::span<float> Face(std::span<float> row, int n, int face) {
  const size_t texels = static_cast<size_t>(n) * n;
  return row.subspan(face * texels, texels);
}

}  // namespace

void RowTransform(WaveletFilter row_filter, int n, std::span<float> row) {
  CheckRowOrDie(n, row);
  const int depth = MaxDepth(n, n);  // full depth: one scaling coefficient per face
  for (int face = 0; face < kFaces; ++face) Forward2d(row_filter, Face(row, n, face), n, n, depth);
}

void InverseRowTransform(WaveletFilter row_filter, int n, std::span<float> row) {
  CheckRowOrDie(n, row);
  const int depth = MaxDepth(n, n);
  for (int face = 0; face < kFaces; ++face) Inverse2d(row_filter, Face(row, n, face), n, n, depth);
}

}  // namespace wavebake
