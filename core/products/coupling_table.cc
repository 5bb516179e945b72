#include "core/products/coupling_table.h"

#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/util/power_of_two.h"

namespace wavebake {
namespace {

// Grid point j of `count` over (lo, hi), endpoints excluded.
double Inside(double lo, double hi, int j, int count) { return lo + (hi - lo) * (j + 0.5) / count; }

}  // namespace

absl::StatusOr<CouplingTable> CouplingTable::Build(const CouplingTableOptions& o) {
  const auto bad = [](const char* field, const auto&... why) {
    return absl::InvalidArgumentError(absl::StrCat("coupling_table.", field, ": ", why...));
  };
  if (!IsPowerOfTwoIn(o.source_res, 2, 4096))
    return bad("source_res", o.source_res, " is not a power of two");
  if (!IsPowerOfTwoIn(o.target_res, 2, 4096))
    return bad("target_res", o.target_res, " is not a power of two");
  if (!(o.s_min > 0 && o.s_max > o.s_min && std::isfinite(o.s_max)))
    return bad("s_min", "need 0 < s_min < s_max (", o.s_min, ", ", o.s_max, ")");
  if (o.scales < 2 || o.offsets < 2 || int64_t{o.scales} * o.offsets > (1 << 22))
    return bad("scales", o.scales, " × offsets ", o.offsets, " is outside 2..2^22 each way");
  const auto t0 = std::chrono::steady_clock::now();
  CouplingTable t;
  t.options_ = o;
  t.factors_ = Haar1dCount(o.source_res);
  t.log_s_min_ = std::log(o.s_min);
  t.log_s_step_ = (std::log(o.s_max) - t.log_s_min_) / (o.scales - 1);
  t.first_.reserve(size_t(o.scales) * o.offsets * t.factors_ + 1);
  t.first_.push_back(0);
  std::vector<Coupling1d> row;
  for (int j = 0; j < o.scales; ++j) {
    const double s = std::exp(t.log_s_min_ + j * t.log_s_step_);
    for (int i = 0; i < o.offsets; ++i) {
      const double off = Inside(-s, 1, i, o.offsets);
      for (int f = 0; f < t.factors_; ++f) {
        row.clear();
        SourceCouplings(Haar1dOf(f), s, off, o.target_res, row);
        t.entries_.insert(t.entries_.end(), row.begin(), row.end());
        t.first_.push_back(static_cast<uint32_t>(t.entries_.size()));
      }
    }
  }
  t.build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

size_t CouplingTable::bytes() const {
  return first_.size() * sizeof(uint32_t) + entries_.size() * sizeof(Coupling1d);
}

std::span<const Coupling1d> CouplingTable::Lookup(int source, double s, double o) const {
  const double js = (std::log(s) - log_s_min_) / log_s_step_;
  if (!(js > -0.5 && js < options_.scales - 0.5)) return {};
  const int j = static_cast<int>(std::lround(js));
  const double grid_s = std::exp(log_s_min_ + j * log_s_step_);
  // o relative to the grid's own (−s, 1) at the snapped scale.
  const double u = (o + grid_s) / (1 + grid_s) * options_.offsets - 0.5;
  if (!(u > -0.5 && u < options_.offsets - 0.5)) return {};
  const int i = static_cast<int>(std::lround(u));
  const size_t cell = (size_t(j) * options_.offsets + i) * factors_ + source;
  return {entries_.data() + first_[cell], entries_.data() + first_[cell + 1]};
}

}  // namespace wavebake
