#include "runtime/gpu/relight_magnitude.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

// The inverse Haar step s of core/wavelets/haar2d.h with every sign +:
// each output of a 2×2 cell is ½(|LL| + |HL| + |LH| + |HH|).
void AbsInverseStep(std::vector<double>& img, int width, int height, int step) {
  const int bw = width >> step, bh = height >> step, hw = bw / 2, hh = bh / 2;
  std::vector<double> out(size_t(bw) * bh);
  for (int j = 0; j < hh; ++j)
    for (int i = 0; i < hw; ++i) {
      const double v =
          0.5 * (img[size_t(j) * width + i] + img[size_t(j) * width + hw + i] +
                 img[size_t(hh + j) * width + i] + img[size_t(hh + j) * width + hw + i]);
      for (int k = 0; k < 4; ++k) out[size_t(2 * j + (k >> 1)) * bw + 2 * i + (k & 1)] = v;
    }
  for (int y = 0; y < bh; ++y)
    for (int x = 0; x < bw; ++x) img[size_t(y) * width + x] = out[size_t(y) * bw + x];
}

}  // namespace

absl::StatusOr<std::vector<float>> RelightMagnitude(const CompressedColumns& t,
                                                    std::span<const WaveletLight> lights) {
  if (t.column_filter != WaveletFilter::kHaar)
    return absl::FailedPreconditionError(
        "store: column_filter is not haar; the GPU's inverse column step is Haar's");
  const size_t cells = size_t(t.width) * t.height;
  int deepest = 0;
  for (const WaveletLight& l : lights) {
    if (l.column >= static_cast<uint32_t>(t.columns))
      return absl::InvalidArgumentError(
          absl::StrCat("lights: column ", l.column, " >= ", t.columns));
    deepest = std::max(deepest, int{t.depth[l.column]});
  }
  // Channel-major planes, as the relighter keeps them.
  std::vector<std::vector<double>> planes(3, std::vector<double>(cells, 0.0));
  for (int d = deepest; d >= 0; --d) {
    for (const WaveletLight& l : lights) {
      if (t.depth[l.column] != d) continue;
      for (int64_t k = t.indptr[l.column]; k < t.indptr[l.column + 1]; ++k)
        for (int c = 0; c < 3; ++c)
          planes[c][t.indices[k]] += std::fabs(double{l.weight[c]} * t.values[k]);
    }
    if (d == 0) break;
    // Below MaxDepth both block sides are ≥ 2: only the 2D step occurs.
    for (auto& p : planes) AbsInverseStep(p, t.width, t.height, d - 1);
  }
  std::vector<float> out(3 * cells);
  for (size_t i = 0; i < cells; ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(planes[c][i]);
  return out;
}

}  // namespace wavebake
