#pragma once
// Non-linear approximation: which coefficients to keep (DESIGN.md §1
// "Coefficient selection", "Relighting"; Ng et al. 2003 via the 4D paper §4.5).
// Importance of coefficient i is its weighted magnitude |v[i]|·w[i] (w: the
// synthesis norms of core/wavelets/subband.h, or empty = all ones). Importance ties are
// broken by lower index, which makes every rule here a total order and every
// result deterministic.
#include <cstdint>
#include <span>
#include <vector>

namespace wavebake {

// The k most important indices, sorted by decreasing importance (k is clamped
// to [0, v.size()]).
std::vector<uint32_t> TopK(std::span<const float> v, std::span<const float> w, int k);

struct Selection {
  std::vector<uint32_t> kept;  // increasing index
  double dropped_energy = 0;   // Σ_{i∉kept} (v_i w_i)²
};

// Smallest set S such that Σ_{i∉S} (v_i w_i)² ≤ energy_budget, keeping the most
// important coefficients first (so S is the top-|S| in the total order above).
// Zero coefficients are never kept (a negative budget keeps every nonzero one).
// Energies and their sums are in double.
// Linear time, no sort: magnitudes are binned by exponent, whole bins are
// dropped while they fit, and only the bin where the budget runs out is
// resolved exactly (median halving).
Selection SelectForBudget(std::span<const float> v, std::span<const float> w, double energy_budget);
// |SelectForBudget(v, w, energy_budget).kept| without building the list (for
// the adaptive depth search, which only compares counts).
int CountForBudget(std::span<const float> v, std::span<const float> w, double energy_budget);

}  // namespace wavebake
