#include "core/separable2d.h"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/wavelet1d.h"

namespace wavebake {
namespace {

// Columns are gathered this many at a time into contiguous lines so the 1D
// kernels read unit-stride memory and each image row is touched once per
// chunk (16 floats = one 64-byte cache line).
constexpr int kColumnChunk = 16;

using LineKernel = void (*)(WaveletFilter, std::span<float>, std::span<float>);

void RowPass(LineKernel kernel, WaveletFilter f, std::span<float> img, int width, int bw, int bh,
             std::span<float> scratch) {
  if (bw < 2) return;
  for (int y = 0; y < bh; ++y) {
    kernel(f, img.subspan(static_cast<size_t>(y) * width, bw), scratch);
  }
}

void ColumnPass(LineKernel kernel, WaveletFilter f, std::span<float> img, int width, int bw, int bh,
                std::span<float> lines, std::span<float> scratch) {
  if (bh < 2) return;
  for (int x0 = 0; x0 < bw; x0 += kColumnChunk) {
    const int nc = std::min(kColumnChunk, bw - x0);
    for (int y = 0; y < bh; ++y) {
      const float* row = img.data() + static_cast<size_t>(y) * width + x0;
      for (int c = 0; c < nc; ++c) lines[static_cast<size_t>(c) * bh + y] = row[c];
    }
    for (int c = 0; c < nc; ++c) kernel(f, lines.subspan(static_cast<size_t>(c) * bh, bh), scratch);
    for (int y = 0; y < bh; ++y) {
      float* row = img.data() + static_cast<size_t>(y) * width + x0;
      for (int c = 0; c < nc; ++c) row[c] = lines[static_cast<size_t>(c) * bh + y];
    }
  }
}

struct StepBuffers {
  std::vector<float> lines, scratch;
  StepBuffers(int bw, int bh)
      : lines(static_cast<size_t>(kColumnChunk) * bh), scratch(std::max(bw, bh)) {}
};

}  // namespace

void SeparableForwardStep(WaveletFilter f, std::span<float> img, int width, int height, int step) {
  const int bw = BlockExtent(width, step), bh = BlockExtent(height, step);
  StepBuffers buf(bw, bh);
  RowPass(Forward1d, f, img, width, bw, bh, buf.scratch);
  ColumnPass(Forward1d, f, img, width, bw, bh, buf.lines, buf.scratch);
}

void SeparableInverseStep(WaveletFilter f, std::span<float> img, int width, int height, int step) {
  const int bw = BlockExtent(width, step), bh = BlockExtent(height, step);
  StepBuffers buf(bw, bh);
  ColumnPass(Inverse1d, f, img, width, bw, bh, buf.lines, buf.scratch);
  RowPass(Inverse1d, f, img, width, bw, bh, buf.scratch);
}

}  // namespace wavebake
