#pragma once
// A Monte-Carlo mean per RGB channel and its standard error by the method of
// batch means: each batch (a fixed number of samples) adds its mean, and the
// spread of those means gives the error of their average.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace wavebake {

struct BatchMeans {
  std::array<double, 3> sum{}, sum_sq{};  // of the batch means
  int64_t batches = 0;

  // One batch's per-channel sums over its `size` samples.
  void Add(const std::array<double, 3>& batch, int size) {
    for (int c = 0; c < 3; ++c) {
      const double mean = batch[c] / size;
      sum[c] += mean;
      sum_sq[c] += mean * mean;
    }
    ++batches;
  }
  double Mean(int c) const { return batches ? sum[c] / batches : 0; }
  // Infinite below two batches (no spread to measure yet).
  double StdErr(int c) const {
    if (batches < 2) return std::numeric_limits<double>::infinity();
    const double var = std::max(0.0, (sum_sq[c] - sum[c] * sum[c] / batches) / (batches - 1));
    return std::sqrt(var / batches);
  }
};

}  // namespace wavebake
