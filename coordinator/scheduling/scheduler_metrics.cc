#include "coordinator/scheduling/scheduler_metrics.h"

#include <algorithm>
#include <cmath>

namespace wavebake {

void LatencyHistogram::Observe(double seconds) {
  if (!(seconds >= 0)) seconds = 0;
  const auto bound = std::lower_bound(kLeaseLatencyBuckets.begin(), kLeaseLatencyBuckets.end(),
                                      seconds);  // Prometheus buckets are "≤ le"
  counts_[bound - kLeaseLatencyBuckets.begin()].fetch_add(1, std::memory_order_relaxed);
  sum_ns_.fetch_add(std::llround(seconds * 1e9), std::memory_order_relaxed);
}

LatencyHistogram::Snapshot LatencyHistogram::Read() const {
  Snapshot s;
  for (size_t i = 0; i < counts_.size(); ++i) s.counts[i] = counts_[i].load();
  // The count is the buckets' sum, so a reader never sees +Inf below a bucket.
  for (int64_t c : s.counts) s.count += c;
  s.sum_seconds = static_cast<double>(sum_ns_.load()) * 1e-9;
  return s;
}

}  // namespace wavebake
