#include "core/columns/count_bounds.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/columns/zero_quads.h"

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

double EnergyHistogram::Lo(int bin) const { return bin == 0 ? 0.0 : FromKey(base_key_ + bin); }

double EnergyHistogram::Hi(int bin) const {
  return std::min(budget_, FromKey(base_key_ + bin + 1));
}

// The body of every add and remove: inlined into the loops below, which
// run over every coefficient of a column at every depth.
template <int kSign>
[[gnu::always_inline]] inline void EnergyHistogram::AddTo(int lane, double e) {
  const int64_t rel = KeyOf(e) - base_key_;  // ≤ kBins − 1 when e ≤ budget
  int b = rel <= 0 ? 0 : static_cast<int>(rel);
  b = e > budget_ ? kAboveSlot : b;
  b = e == 0 ? kZeroSlot : b;
  count_[lane][b] += kSign;
  energy_[lane][b] += kSign * e;  // exact for kSign = ±1
}

template <int kSign>
void EnergyHistogram::Update(std::span<const float> v, std::span<const float> w) {
  const size_t n = v.size();
  if (!w.empty()) {
    for (size_t i = 0; i < n; ++i) {
      const double m = double(v[i]) * w[i];
      AddTo<kSign>(i & 1, m * m);
    }
    return;
  }
  ForNonzeroQuads(v.data(), n, [&](size_t i) {
    const double m = v[i];
    AddTo<kSign>(i & 1, m * m);
  });
}

void EnergyHistogram::Add(std::span<const float> v, std::span<const float> w) { Update<1>(v, w); }
void EnergyHistogram::Remove(std::span<const float> v, std::span<const float> w) {
  Update<-1>(v, w);
}

namespace {

// How many of a bin's `count` entries fit in what is left of a budget,
// `left`, when each may weigh `per_entry` (Lo or Hi of the bin).
int64_t Partial(double left, double per_entry, int64_t count) {
  const int64_t fit = per_entry > 0 ? static_cast<int64_t>(std::floor(left / per_entry)) : count;
  return std::min(count, fit);
}

}  // namespace

CountBounds EnergyHistogram::Bounds() const {
  int64_t nonzero = count_[0][kAboveSlot] + count_[1][kAboveSlot];
  for (int b = 0; b < kBins; ++b) nonzero += count_[0][b] + count_[1][b];
  if (budget_ <= 0) return {static_cast<int>(nonzero), static_cast<int>(nonzero)};
  // The least important entries that fit, for the budget narrowed (the
  // upper bound on the count: whole bins, then Hi per entry in the cut bin)
  // and widened (the lower bound: Lo per entry). One walk serves both: the
  // bins dropped whole are the same prefix, the wider budget may go on.
  const double narrow = budget_ * (1 - kSlack), wide = budget_ * (1 + kSlack);
  double dropped = 0;
  int64_t k = 0, fit_narrow = -1, fit_wide = -1;
  for (int b = 0; b < kBins; ++b) {
    const int64_t count = count_[0][b] + count_[1][b];
    if (count == 0) continue;
    const double energy = energy_[0][b] + energy_[1][b];
    if (fit_narrow < 0 && dropped + energy > narrow)
      fit_narrow = k + Partial(std::max(0.0, narrow - dropped), Hi(b), count);
    if (dropped + energy > wide) {
      fit_wide = k + Partial(std::max(0.0, wide - dropped), Lo(b), count);
      break;
    }
    dropped += energy;
    k += count;
  }
  if (fit_narrow < 0) fit_narrow = k;
  if (fit_wide < 0) fit_wide = k;
  return {static_cast<int>(nonzero - fit_wide), static_cast<int>(nonzero - fit_narrow)};
}

}  // namespace wavebake
