#include "core/count_bounds.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace wavebake {
namespace {

// Exponent and the top 2 mantissa bits of a positive double: monotone in
// the value, 4 bins per binade.
constexpr int kKeyShift = 50;
int64_t KeyOf(double e) { return static_cast<int64_t>(std::bit_cast<uint64_t>(e) >> kKeyShift); }
double FromKey(int64_t key) {
  return std::bit_cast<double>(static_cast<uint64_t>(key) << kKeyShift);
}

constexpr double kSlack = 1e-6;  // relative widening/narrowing of the budget in the walks

}  // namespace

EnergyHistogram::EnergyHistogram(double budget)
    : budget_(budget),
      base_key_(budget > 0 ? std::max<int64_t>(0, KeyOf(budget) - (kBins - 1)) : 0) {}

int EnergyHistogram::BinOf(double e) const {
  const int64_t rel = KeyOf(e) - base_key_;  // ≤ kBins − 1 since e ≤ budget
  return rel <= 0 ? 0 : static_cast<int>(rel);
}

double EnergyHistogram::Lo(int bin) const { return bin == 0 ? 0.0 : FromKey(base_key_ + bin); }

double EnergyHistogram::Hi(int bin) const {
  return std::min(budget_, FromKey(base_key_ + bin + 1));
}

void EnergyHistogram::Update(std::span<const float> v, std::span<const float> w, int sign) {
  auto one = [&](double m) {
    const double e = m * m;
    if (e == 0) return;  // dropped first whatever the budget: never counted
    if (!(e <= budget_)) {
      above_ += sign;
      return;
    }
    const int b = BinOf(e);
    count_[b] += sign;
    energy_[b] += sign * e;
  };
  if (w.empty()) {
    for (float x : v) one(x);
  } else {
    for (size_t i = 0; i < v.size(); ++i) one(double(v[i]) * w[i]);
  }
}

void EnergyHistogram::Add(std::span<const float> v, std::span<const float> w) { Update(v, w, 1); }
void EnergyHistogram::Remove(std::span<const float> v, std::span<const float> w) {
  Update(v, w, -1);
}

int64_t EnergyHistogram::Droppable(double budget, bool optimistic) const {
  double dropped = 0;
  int64_t k = 0;
  for (int b = 0; b < kBins; ++b) {
    if (count_[b] == 0) continue;
    if (dropped + energy_[b] <= budget) {
      dropped += energy_[b];
      k += count_[b];
      continue;
    }
    const double left = std::max(0.0, budget - dropped);
    const double per_entry = optimistic ? Lo(b) : Hi(b);
    const int64_t partial =
        per_entry > 0 ? static_cast<int64_t>(std::floor(left / per_entry)) : count_[b];
    return k + std::min(count_[b], partial);
  }
  return k;
}

CountBounds EnergyHistogram::Bounds() const {
  int64_t nonzero = above_;
  for (int64_t c : count_) nonzero += c;
  if (budget_ <= 0) return {static_cast<int>(nonzero), static_cast<int>(nonzero)};
  return {static_cast<int>(nonzero - Droppable(budget_ * (1 + kSlack), true)),
          static_cast<int>(nonzero - Droppable(budget_ * (1 - kSlack), false))};
}

}  // namespace wavebake
