#include "core/nla.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace wavebake {
namespace {

// |v_i·w_i| in double: a float×float product is exact there (48 significant
// bits), so the order never depends on rounding.
double Magnitude(std::span<const float> v, std::span<const float> w, size_t i) {
  const double x = static_cast<double>(v[i]) * (w.empty() ? 1.0 : static_cast<double>(w[i]));
  return std::fabs(x);
}

struct Entry {
  double mag;
  uint32_t index;
};

// The total importance order: larger magnitude first, then lower index.
bool LessImportant(const Entry& a, const Entry& b) {
  return a.mag < b.mag || (a.mag == b.mag && a.index > b.index);
}

struct Cut {
  size_t kept = 0;  // how many of the nonzero entries are kept
  double dropped_energy = 0;
  Entry least_kept{0, 0};  // valid when kept > 0
};

// Drops the least important nonzero entries while their energy fits the
// budget. Invariant: entries[0, lo) are dropped and the least important of all,
// entries[hi, n) are kept and the most important; each round splits [lo, hi) at
// its median (std::nth_element), drops the lower half plus the median if they
// still fit, else keeps the median and everything above it. O(n) expected.
Cut FindCut(std::span<const float> v, std::span<const float> w, double budget,
            std::vector<Entry>& entries) {
  entries.clear();
  double total = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    const double m = Magnitude(v, w, i);
    if (m > 0) {
      entries.push_back({m, static_cast<uint32_t>(i)});
      total += m * m;
    }
  }
  Cut cut;
  if (total <= budget) {
    cut.dropped_energy = total;
    return cut;
  }
  size_t lo = 0, hi = entries.size();
  double dropped = 0;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    std::nth_element(entries.begin() + lo, entries.begin() + mid, entries.begin() + hi,
                     LessImportant);
    double s = 0;
    for (size_t i = lo; i <= mid; ++i) s += entries[i].mag * entries[i].mag;
    if (dropped + s <= budget) {
      dropped += s;
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  cut.kept = entries.size() - lo;
  cut.dropped_energy = dropped;
  if (cut.kept > 0) {
    cut.least_kept = *std::min_element(entries.begin() + lo, entries.end(), LessImportant);
  }
  return cut;
}

std::vector<Entry>& Scratch() {
  thread_local std::vector<Entry> entries;
  return entries;
}

}  // namespace

std::vector<uint32_t> TopK(std::span<const float> v, std::span<const float> w, int k) {
  const size_t n = v.size();
  const size_t kk = static_cast<size_t>(std::clamp<long long>(k, 0, static_cast<long long>(n)));
  std::vector<Entry> entries(n);
  for (size_t i = 0; i < n; ++i) entries[i] = {Magnitude(v, w, i), static_cast<uint32_t>(i)};
  auto more_important = [](const Entry& a, const Entry& b) { return LessImportant(b, a); };
  std::partial_sort(entries.begin(), entries.begin() + kk, entries.end(), more_important);
  std::vector<uint32_t> out(kk);
  for (size_t i = 0; i < kk; ++i) out[i] = entries[i].index;
  return out;
}

Selection SelectForBudget(std::span<const float> v, std::span<const float> w,
                          double energy_budget) {
  const Cut cut = FindCut(v, w, energy_budget, Scratch());
  Selection sel;
  sel.dropped_energy = cut.dropped_energy;
  if (cut.kept == 0) return sel;
  // Everything at least as important as the least important kept entry is
  // kept; scanning in index order gives the list sorted without a sort.
  sel.kept.reserve(cut.kept);
  for (size_t i = 0; i < v.size(); ++i) {
    const Entry e{Magnitude(v, w, i), static_cast<uint32_t>(i)};
    if (e.mag > 0 && !LessImportant(e, cut.least_kept)) sel.kept.push_back(e.index);
  }
  return sel;
}

int CountForBudget(std::span<const float> v, std::span<const float> w, double energy_budget) {
  return static_cast<int>(FindCut(v, w, energy_budget, Scratch()).kept);
}

}  // namespace wavebake
