#include "core/wavelets/subband.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "core/wavelets/separable2d.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {

Subband SubbandAt(int x, int y, int width, int height, int depth) {
  if (depth <= 0) return {0, 0};
  if (x < BlockExtent(width, depth) && y < BlockExtent(height, depth)) return {0, 0};
  // The innermost step block that contains (x, y) is the step that produced it.
  for (int s = depth - 1; s >= 0; --s) {
    const int bw = BlockExtent(width, s), bh = BlockExtent(height, s);
    if (x >= bw || y >= bh) continue;
    const bool hx = bw > 1 && x >= BlockExtent(width, s + 1);
    const bool hy = bh > 1 && y >= BlockExtent(height, s + 1);
    return {depth - 1 - s, (hx ? 1 : 0) + (hy ? 2 : 0)};
  }
  return {0, 0};  // outside the image: not a coefficient
}

namespace {

bool IsOrthonormalFilter(WaveletFilter f) {
  return f == WaveletFilter::kHaar || f == WaveletFilter::kDaub4;
}

// ‖Inverse2d(unit impulse at (x, y))‖₂, accumulated in double.
double ImpulseNorm(WaveletFilter f, int x, int y, int width, int height, int depth) {
  std::vector<float> img(static_cast<size_t>(width) * height, 0.0f);
  img[static_cast<size_t>(y) * width + x] = 1;
  Inverse2d(f, img, width, height, depth);
  double sum = 0;
  for (float v : img) sum += static_cast<double>(v) * v;
  return std::sqrt(sum);
}

// Centre of subband (level, band): the LL block, or a quarter of step s's block.
std::pair<int, int> SubbandCentre(Subband sb, int width, int height, int depth) {
  if (sb.band == 0) return {BlockExtent(width, depth) / 2, BlockExtent(height, depth) / 2};
  const int s = depth - 1 - sb.level;
  const int bw = BlockExtent(width, s), bh = BlockExtent(height, s);
  const int hw = BlockExtent(width, s + 1), hh = BlockExtent(height, s + 1);
  const int x = (sb.band & 1) ? hw + (bw - hw) / 2 : hw / 2;
  const int y = (sb.band & 2) ? hh + (bh - hh) / 2 : hh / 2;
  return {x, y};
}

std::vector<float> ComputeNorms(WaveletFilter f, int width, int height, int depth) {
  std::vector<float> out(static_cast<size_t>(width) * height, 1.0f);
  if (depth <= 0 || IsOrthonormalFilter(f)) return out;
  // norm[level][band]; band 0 only at level 0.
  std::vector<std::array<float, 4>> norm(depth, {0, 0, 0, 0});
  norm[0][0] = float(ImpulseNorm(f, BlockExtent(width, depth) / 2, BlockExtent(height, depth) / 2,
                                 width, height, depth));
  for (int level = 0; level < depth; ++level) {
    for (int band = 1; band < 4; ++band) {
      const auto [x, y] = SubbandCentre({level, band}, width, height, depth);
      norm[level][band] = float(ImpulseNorm(f, x, y, width, height, depth));
    }
  }
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Subband sb = SubbandAt(x, y, width, height, depth);
      out[static_cast<size_t>(y) * width + x] = norm[sb.level][sb.band];
    }
  }
  return out;
}

}  // namespace

const std::vector<float>& SynthesisNormsRef(WaveletFilter f, int width, int height, int depth) {
  using Key = std::tuple<WaveletFilter, int, int, int>;
  static std::mutex mu;
  // Never erased, so references handed out stay valid.
  static std::map<Key, std::unique_ptr<const std::vector<float>>> cache;
  std::lock_guard<std::mutex> lock(mu);
  auto& slot = cache[Key{f, width, height, depth}];
  if (!slot) {
    slot = std::make_unique<const std::vector<float>>(ComputeNorms(f, width, height, depth));
  }
  return *slot;
}

std::vector<float> SynthesisNorms(WaveletFilter f, int width, int height, int depth) {
  return SynthesisNormsRef(f, width, height, depth);
}

int RowLevel(int x, int y) {
  const unsigned m = static_cast<unsigned>(std::max(x, y));
  return m == 0 ? 0 : std::bit_width(m);  // bit_width(m) = 1 + floor(log2 m)
}

}  // namespace wavebake
