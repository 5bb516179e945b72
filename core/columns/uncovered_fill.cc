#include "core/columns/uncovered_fill.h"

#include <algorithm>

namespace wavebake {
namespace {

// Dilation order: every uncovered cell at Chebyshev distance k copies its
// first neighbour (in this order) at distance k − 1.
constexpr int kNeighbours[8][2] = {{0, -1},  {0, 1},  {-1, 0}, {1, 0},
                                   {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};

}  // namespace

CellFiller::CellFiller(UncoveredFill kind, std::span<const int32_t> grid, int width, int height,
                       int max_distance)
    : kind_(kind), width_(width), covered_(grid.size()) {
  for (size_t i = 0; i < grid.size(); ++i) covered_[i] = grid[i] >= 0;
  {
    std::vector<uint32_t> level(covered_.begin(), covered_.end());
    int w = width, h = height;
    counts_.push_back(level);
    sizes_.push_back({w, h});
    while (w > 1 || h > 1) {
      const int pw = std::max(1, w / 2), ph = std::max(1, h / 2);
      std::vector<uint32_t> parent(size_t(pw) * ph, 0);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          parent[size_t(y * ph / h) * pw + x * pw / w] += level[size_t(y) * w + x] > 0;
      counts_.push_back(parent);
      sizes_.push_back({pw, ph});
      level = std::move(parent);
      w = pw, h = ph;
    }
  }
  if (kind == UncoveredFill::kDilate) {
    // Breadth-first from the covered cells; `from` is the copy source.
    std::vector<int> distance(grid.size(), -1);
    std::vector<uint32_t> frontier;
    for (uint32_t i = 0; i < grid.size(); ++i)
      if (covered_[i]) distance[i] = 0, frontier.push_back(i);
    for (int d = 1; d <= max_distance && !frontier.empty(); ++d) {
      std::vector<uint32_t> next;
      for (uint32_t c : frontier) {
        const int cx = int(c % width), cy = int(c / width);
        for (const auto& [dx, dy] : kNeighbours) {
          const int x = cx + dx, y = cy + dy;
          if (x < 0 || y < 0 || x >= width || y >= height) continue;
          const uint32_t n = uint32_t(y) * width + x;
          if (distance[n] < 0) distance[n] = d, next.push_back(n);
        }
      }
      std::sort(next.begin(), next.end());
      for (uint32_t n : next) {  // the source: the first neighbour one step closer
        const int nx = int(n % width), ny = int(n / width);
        for (const auto& [dx, dy] : kNeighbours) {
          const int x = nx + dx, y = ny + dy;
          if (x < 0 || y < 0 || x >= width || y >= height) continue;
          const uint32_t s = uint32_t(y) * width + x;
          if (distance[s] == d - 1) {
            copies_.push_back({n, s});
            break;
          }
        }
      }
      frontier = std::move(next);
    }
  }
}

void CellFiller::Fill(std::span<float> values, int channels) const {
  const size_t cells = covered_.size();
  switch (kind_) {
    case UncoveredFill::kZero:
      for (size_t i = 0; i < cells; ++i)
        if (!covered_[i]) std::fill_n(values.begin() + i * channels, channels, 0.0f);
      return;
    case UncoveredFill::kPushPull:
      return PushPull(values, channels);
    case UncoveredFill::kDilate:
      for (const auto& [dst, src] : copies_)
        std::copy_n(values.begin() + size_t(src) * channels, channels,
                    values.begin() + size_t(dst) * channels);
      return;
  }
}

void CellFiller::ZeroUncoveredCoefficients(std::span<float> layout, int depth) const {
  if (depth <= 0 || static_cast<size_t>(depth) >= counts_.size()) return;
  // The coefficient at (x, y) of step s's block [0, W_s) × [0, H_s) (W_s =
  // BlockExtent(W, s)) reaches the level-(s+1) block (x mod W_{s+1}, y mod
  // H_{s+1}); the scaling coefficients of the LL block reach their own block.
  for (int s = depth - 1; s >= 0; --s) {
    const auto [bw, bh] = sizes_[s];
    const auto [cw, ch] = sizes_[s + 1];
    const std::vector<uint32_t>& blocks = counts_[s + 1];
    for (int y = 0; y < bh; ++y)
      for (int x = 0; x < bw; ++x) {
        const bool scaling = x < cw && y < ch;
        if (scaling && s != depth - 1) continue;  // a detail of a deeper step
        if (blocks[size_t(y % ch) * cw + x % cw] == 0) layout[size_t(y) * width_ + x] = 0;
      }
  }
}

void CellFiller::PushPull(std::span<float> values, int channels) const {
  // Pull: block sums over covered cells (in double), level by level.
  const size_t levels = counts_.size();
  std::vector<std::vector<double>> sums(levels);
  sums[0].assign(covered_.size() * channels, 0.0);
  for (size_t i = 0; i < covered_.size(); ++i)
    if (covered_[i])
      for (int c = 0; c < channels; ++c) sums[0][i * channels + c] = values[i * channels + c];
  for (size_t l = 1; l < levels; ++l) {
    const auto [w, h] = sizes_[l - 1];
    const auto [pw, ph] = sizes_[l];
    sums[l].assign(size_t(pw) * ph * channels, 0.0);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        if (counts_[l - 1][i] == 0) continue;
        for (int c = 0; c < channels; ++c)  // the child's mean
          sums[l][(size_t(y * ph / h) * pw + x * pw / w) * channels + c] +=
              sums[l - 1][i * channels + c] / counts_[l - 1][i];
      }
    }
  }
  // Push: a block's mean, or its parent's pushed value when it has no coverage.
  std::vector<double> pushed(channels, 0.0), below;
  if (counts_.back()[0] > 0)
    for (int c = 0; c < channels; ++c) pushed[c] = sums.back()[c] / counts_.back()[0];
  for (size_t l = levels - 1; l-- > 0;) {
    const auto [w, h] = sizes_[l];
    const auto [pw, ph] = sizes_[l + 1];
    below.assign(size_t(w) * h * channels, 0.0);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x, p = size_t(y * ph / h) * pw + x * pw / w;
        for (int c = 0; c < channels; ++c)
          below[i * channels + c] = counts_[l][i] > 0 ? sums[l][i * channels + c] / counts_[l][i]
                                                      : pushed[p * channels + c];
      }
    }
    pushed.swap(below);
  }
  for (size_t i = 0; i < covered_.size(); ++i)
    if (!covered_[i])
      for (int c = 0; c < channels; ++c) values[i * channels + c] = float(pushed[i * channels + c]);
}

}  // namespace wavebake
