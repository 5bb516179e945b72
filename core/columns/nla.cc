#include "core/columns/nla.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <optional>

#include "core/columns/zero_quads.h"

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

// Magnitudes are binned by the top 15 bits of their double representation
// (exponent + 4 mantissa bits: bins 2^(1/16) wide), relative to the largest
// one. The bit pattern of a positive double is monotone in its value, so bins
// are ordered like the magnitudes; everything 64 binades below the maximum
// shares bin 0. Binning is only a coarse pre-sort: the one bin where the
// budget runs out is resolved exactly below.
constexpr int kBins = 1024;

int BinOf(double mag, uint64_t max_top) {
  const uint64_t rel = max_top - (std::bit_cast<uint64_t>(mag) >> 48);
  return rel >= kBins - 1 ? 0 : kBins - 1 - static_cast<int>(rel);
}

struct Cut {
  int bin = kBins;  // entries in higher bins are kept, lower ones dropped
  uint64_t max_top = 0;
  size_t kept = 0;         // total kept (nonzero) entries
  size_t kept_in_bin = 0;  // kept entries inside `bin`
  Entry least_kept{0, 0};  // least important kept entry of `bin` (if kept_in_bin > 0)
  double dropped_energy = 0;
};

// Inside one bin: drops the least important entries while their energy fits.
// Invariant: entries[0, lo) are dropped and the least important, entries[hi, n)
// kept and the most important; each round splits [lo, hi) at its median
// (std::nth_element) and drops the lower half plus the median if they still
// fit, else keeps the median and everything above it. O(n).
size_t DropWithinBin(std::vector<Entry>& entries, double budget, double& dropped) {
  size_t lo = 0, hi = entries.size();
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
  return lo;
}

// What FindCut computed per entry, kept for the caller's next pass over the
// same column (SelectForBudget): each magnitude and bin is worked out once,
// for the nonzero entries only — most coefficients of a transport column are
// exactly 0 (two thirds on the bunny), and every pass after the first runs
// over the compact list. Zeros add nothing to any sum and are never kept, so
// the results are those of passes over every entry. Per thread, reused
// column after column; the bins hold zeros between calls.
struct CutScratch {
  // The nonzero entries [0, nonzero): the buffers only grow (a resize up
  // would zero-fill them for every column).
  size_t nonzero = 0;
  std::vector<uint32_t> index;  // increasing
  std::vector<double> mag;      // Magnitude(v, w, index[k])
  std::vector<uint16_t> bin;    // BinOf(mag[k])
  std::array<double, kBins> energy{};
  std::array<uint32_t, kBins> count{};
  std::array<uint64_t, kBins / 64> occupied{};  // bit b: count[b] > 0
  std::vector<Entry> entries;                   // the cut bin's entries
};

CutScratch& ThreadCutScratch() {
  thread_local CutScratch scratch;
  return scratch;
}

// The nonzero entries with their magnitudes and their largest magnitude.
// Quads of zeros are skipped, the rest compacted without a branch per entry:
// whether an entry is 0 follows no pattern a predictor learns.
void Gather(std::span<const float> v, std::span<const float> w, CutScratch& s, double& max_mag) {
  const size_t n = v.size();
  if (s.index.size() < n + 1) {
    s.index.resize(n + 1);
    s.mag.resize(n + 1);
    s.bin.resize(n + 1);
  }
  uint32_t* index = s.index.data();
  double* mag = s.mag.data();
  size_t count = 0;
  auto add = [&](size_t i) {
    const double m = Magnitude(v, w, i);
    index[count] = static_cast<uint32_t>(i);
    mag[count] = m;
    count += m != 0;  // a zero value or a zero weight
  };
  if (w.empty()) {
    ForNonzeroQuads(v.data(), n, add);
  } else {
    for (size_t i = 0; i < n; ++i) add(i);
  }
  s.nonzero = count;
  double max_m[4] = {0, 0, 0, 0};  // four chains: the max is the same in any order
  size_t k = 0;
  for (; k + 4 <= count; k += 4)
    for (int j = 0; j < 4; ++j) max_m[j] = std::max(max_m[j], mag[k + j]);
  for (; k < count; ++k) max_m[0] = std::max(max_m[0], mag[k]);
  max_mag = std::max(std::max(max_m[0], max_m[1]), std::max(max_m[2], max_m[3]));
}

// Σ m² in index order (one dependent chain of adds) when it is within
// rounding of `budget` or below: whether everything fits, and the dropped
// energy if it does. Four interleaved partial sums differ from the ordered
// sum by far less than 1e-9 relative (n·2⁻⁵³ with n < 2³²), so when they
// exceed the budget by more, the ordered sum does too and is not needed.
std::optional<double> TotalIfWithin(std::span<const double> mag, double budget) {
  double part[4] = {0, 0, 0, 0};
  size_t k = 0;
  for (; k + 4 <= mag.size(); k += 4)
    for (int j = 0; j < 4; ++j) part[j] += mag[k + j] * mag[k + j];
  for (; k < mag.size(); ++k) part[0] += mag[k] * mag[k];
  if ((part[0] + part[1]) + (part[2] + part[3]) > budget * (1 + 1e-9)) return std::nullopt;
  double total = 0;
  for (double m : mag) total += m * m;
  if (total > budget) return std::nullopt;
  return total;
}

Cut FindCut(std::span<const float> v, std::span<const float> w, double budget, CutScratch& s) {
  Cut cut;
  double max_mag = 0;
  Gather(v, w, s, max_mag);
  if (const std::optional<double> total =
          TotalIfWithin(std::span(s.mag).first(s.nonzero), budget)) {
    cut.dropped_energy = *total;
    return cut;
  }
  cut.max_top = std::bit_cast<uint64_t>(max_mag) >> 48;
  const size_t n = s.nonzero;
  for (size_t k = 0; k < n; ++k) {
    const double m = s.mag[k];
    const int b = BinOf(m, cut.max_top);
    s.bin[k] = static_cast<uint16_t>(b);
    s.energy[b] += m * m;
    ++s.count[b];
    s.occupied[b / 64] |= uint64_t{1} << (b % 64);
  }
  // Whole bins go while they fit (empty ones add nothing, so only occupied
  // ones are visited); the first that does not is the cut bin.
  double dropped = 0;
  size_t below = 0;  // entries in the bins dropped whole
  int b = kBins;
  for (int word = 0; word < kBins / 64 && b == kBins; ++word) {
    for (uint64_t bits = s.occupied[word]; bits != 0; bits &= bits - 1) {
      const int k = word * 64 + std::countr_zero(bits);
      if (dropped + s.energy[k] > budget) {
        b = k;
        break;
      }
      dropped += s.energy[k];
      below += s.count[k];
    }
  }
  cut.bin = b;  // < kBins, since total > budget
  // Raw pointers: the entries' stores could otherwise alias the scratch's
  // vectors, which the loop would reload on every entry.
  s.entries.resize(s.count[b] + 1);  // one past: the branch-free writes
  Entry* in_bin = s.entries.data();
  const uint16_t* bin = s.bin.data();
  const double* mag = s.mag.data();
  const uint32_t* index = s.index.data();
  for (size_t k = 0, at = 0; k < n; ++k) {
    in_bin[at] = {mag[k], index[k]};
    at += bin[k] == b;
  }
  s.entries.pop_back();
  const size_t lo = DropWithinBin(s.entries, budget, dropped);
  cut.kept_in_bin = s.entries.size() - lo;
  if (cut.kept_in_bin > 0) {
    cut.least_kept = *std::min_element(s.entries.begin() + lo, s.entries.end(), LessImportant);
  }
  cut.kept = n - below - s.entries.size() + cut.kept_in_bin;
  cut.dropped_energy = dropped;
  // Ready for the next column: only the occupied bins hold anything.
  for (int word = 0; word < kBins / 64; ++word) {
    for (uint64_t bits = s.occupied[word]; bits != 0; bits &= bits - 1) {
      const int k = word * 64 + std::countr_zero(bits);
      s.energy[k] = 0;
      s.count[k] = 0;
    }
    s.occupied[word] = 0;
  }
  return cut;
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
  CutScratch& s = ThreadCutScratch();
  const Cut cut = FindCut(v, w, energy_budget, s);
  Selection sel;
  sel.dropped_energy = cut.dropped_energy;
  if (cut.kept == 0) return sel;
  // Kept: every entry in a bin above the cut bin, and those of the cut bin at
  // least as important as its least important kept entry. Scanning in index
  // order gives the list sorted without a sort; written without a branch
  // per entry (kept or not follows no pattern), through raw pointers (the
  // output would otherwise make the compiler reload the scratch's).
  const size_t n = s.nonzero;
  sel.kept.resize(cut.kept + 1);  // one past: the branch-free writes
  uint32_t* out = sel.kept.data();
  const uint32_t* index = s.index.data();
  const double* mag = s.mag.data();
  const uint16_t* bin = s.bin.data();
  const bool any_in_bin = cut.kept_in_bin > 0;
  size_t count = 0;
  for (size_t k = 0; k < n; ++k) {
    const int b = bin[k];
    const bool keep = b > cut.bin || (b == cut.bin && any_in_bin &&
                                      !LessImportant({mag[k], index[k]}, cut.least_kept));
    out[count] = index[k];
    count += keep;
  }
  sel.kept.resize(count);
  return sel;
}

int CountForBudget(std::span<const float> v, std::span<const float> w, double energy_budget) {
  return static_cast<int>(FindCut(v, w, energy_budget, ThreadCutScratch()).kept);
}

}  // namespace wavebake
