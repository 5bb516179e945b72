#pragma once
// Cheap bounds on core/columns/nla.h CountForBudget for the adaptive depth search
// (DESIGN.md §1; 4D paper §4.2): the search compares kept-coefficient counts
// across depths, and an exact count per depth costs several passes and a
// selection; bounds from one histogram settle most comparisons, and exact
// counts are taken only where they do not.
//
// The count is n_nonzero − k, k the longest run of least important
// coefficients whose energies e = (c·w)² sum to ≤ budget. Energies ≤ budget
// are binned by their double's bit pattern (exponent and 2 mantissa bits:
// quarter-mantissa bins with exact power-of-two-based edges) over the 64
// binades below the budget; smaller ones share one bin whose lower edge is 0,
// and energies above the budget are only counted (they are always kept).
// Whole bins are dropped while they fit; in the bin where the budget runs
// out, between floor(R/hi) and floor(R/lo) of its entries fit in what is
// left, R. Bin sums are kept in double and may carry rounding from adds and
// removes, so the walks use the budget widened (and narrowed) by 1e-6.
#include <array>
#include <cstdint>
#include <span>

namespace wavebake {

struct CountBounds {
  int lower = 0, upper = 0;  // lower ≤ CountForBudget(...) ≤ upper
};

class EnergyHistogram {
 public:
  explicit EnergyHistogram(double budget);

  // Adds (or removes) the coefficients v (weights w, empty = ones).
  void Add(std::span<const float> v, std::span<const float> w = {});
  void Remove(std::span<const float> v, std::span<const float> w = {});
  CountBounds Bounds() const;

 private:
  static constexpr int kBins = 4 * 64 + 1;  // bin 0: everything far below the budget
  // Two more slots, so that every entry lands in one without a branch: exact
  // zeros (never counted) and entries above the budget (always kept).
  static constexpr int kZeroSlot = kBins, kAboveSlot = kBins + 1, kSlots = kBins + 2;
  template <int kSign>
  void Update(std::span<const float> v, std::span<const float> w);
  // Adds (kSign = 1) or removes (−1) entry energy e in lane `lane` (two
  // lanes: consecutive entries in the same bin do not wait for each other's
  // store).
  template <int kSign>
  void AddTo(int lane, double e);
  double Lo(int bin) const;
  double Hi(int bin) const;

  double budget_;
  int64_t base_key_;  // bit key of bin 1's lower edge
  std::array<std::array<int64_t, kSlots>, 2> count_{};
  std::array<std::array<double, kSlots>, 2> energy_{};
};

}  // namespace wavebake
