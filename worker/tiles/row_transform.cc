#include "worker/tiles/row_transform.h"

#include <cstdio>
#include <cstdlib>

#include "core/util/power_of_two.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

// The row's shape is fixed by the job's BakeParams, so a mismatch is a
// programming error, not bad input (as in core/transport/transport_row.cc). Returns
// the number of faces: 6 (cube) or 1 (plane light domain).
int FacesOrDie(int n, std::span<const float> row) {
  if (IsPowerOfTwo(n)) {
    const size_t face = static_cast<size_t>(n) * n;
    if (row.size() == 6 * face) return 6;
    if (row.size() == face) return 1;
  }
  std::fprintf(stderr, "RowTransform: row of %zu entries is not 6·n² or n² for n=%d a power of 2\n",
               row.size(), n);
  std::abort();
}

std::span<float> Face(std::span<float> row, int n, int face) {
  const size_t texels = static_cast<size_t>(n) * n;
  return row.subspan(face * texels, texels);
}

}  // namespace

void RowTransform(WaveletFilter row_filter, int n, std::span<float> row) {
  const int faces = FacesOrDie(n, row);
  const int depth = MaxDepth(n, n);  // full depth: one scaling coefficient per face
  for (int face = 0; face < faces; ++face) Forward2d(row_filter, Face(row, n, face), n, n, depth);
}

void InverseRowTransform(WaveletFilter row_filter, int n, std::span<float> row) {
  const int faces = FacesOrDie(n, row);
  const int depth = MaxDepth(n, n);
  for (int face = 0; face < faces; ++face) Inverse2d(row_filter, Face(row, n, face), n, n, depth);
}

}  // namespace wavebake
