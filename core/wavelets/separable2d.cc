#include "core/wavelets/separable2d.h"

#include <algorithm>
#include <cstddef>

#include "core/wavelets/daub4_1d.h"
#include "core/wavelets/lifting_rows.h"
#include "core/wavelets/thread_scratch.h"
#include "core/wavelets/wavelet1d.h"

namespace wavebake {
namespace {

// Columns of Haar (used here only for 1-wide blocks) are gathered this many
// at a time into contiguous lines so the 1D kernel reads unit-stride memory
// (16 floats = one 64-byte cache line). Daubechies-4 and the lifting filters
// instead run along y with each row as one sample (core/wavelets/daub4_1d.h,
// core/wavelets/lifting_rows.h): unit stride and no gather.
constexpr int kColumnChunk = 16;

using LineKernel = void (*)(WaveletFilter, std::span<float>, std::span<float>);

bool IsLifting(WaveletFilter f) {
  return f == WaveletFilter::kLeGall53 || f == WaveletFilter::kCdf97;
}

LiftingScheme SchemeOf(WaveletFilter f) {
  return f == WaveletFilter::kLeGall53 ? LeGall53Scheme() : Cdf97Scheme();
}

void RowPass(LineKernel kernel, WaveletFilter f, std::span<float> img, int width, int bw, int bh) {
  if (bw < 2) return;
  std::span<float> scratch = ThreadScratch(ScratchSlot::kLine, bw);
  for (int y = 0; y < bh; ++y) {
    kernel(f, img.subspan(static_cast<size_t>(y) * width, bw), scratch);
  }
}

void GatheredColumnPass(LineKernel kernel, WaveletFilter f, std::span<float> img, int width, int bw,
                        int bh) {
  std::span<float> lines =
      ThreadScratch(ScratchSlot::kBlock, static_cast<size_t>(kColumnChunk) * bh);
  std::span<float> scratch = ThreadScratch(ScratchSlot::kLine, bh);
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

}  // namespace

void SeparableForwardStep(WaveletFilter f, std::span<float> img, int width, int height, int step) {
  const int bw = BlockExtent(width, step), bh = BlockExtent(height, step);
  RowPass(Forward1d, f, img, width, bw, bh);
  if (bh < 2) return;
  if (IsLifting(f)) {
    LiftingForwardRows(SchemeOf(f), img, width, bw, bh);
  } else if (f == WaveletFilter::kDaub4) {
    Daub4ForwardRows(img, width, bw, bh);
  } else {
    GatheredColumnPass(Forward1d, f, img, width, bw, bh);
  }
}

void SeparableInverseStep(WaveletFilter f, std::span<float> img, int width, int height, int step) {
  const int bw = BlockExtent(width, step), bh = BlockExtent(height, step);
  if (bh >= 2) {
    if (IsLifting(f)) {
      LiftingInverseRows(SchemeOf(f), img, width, bw, bh);
    } else if (f == WaveletFilter::kDaub4) {
      Daub4InverseRows(img, width, bw, bh);
    } else {
      GatheredColumnPass(Inverse1d, f, img, width, bw, bh);
    }
  }
  RowPass(Inverse1d, f, img, width, bw, bh);
}

}  // namespace wavebake
