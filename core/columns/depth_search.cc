#include "core/columns/depth_search.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

#include "core/columns/count_bounds.h"
#include "core/columns/nla.h"
#include "core/wavelets/separable2d.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

// Per-thread buffers, reused column after column: allocating per column
// would cost more than the search.
struct SearchScratch {
  std::vector<float> work;       // the column transformed to the deepest depth tried
  std::vector<float> blocks;     // LL block of every depth d ≥ 1 before step d, concatenated
  std::vector<size_t> block_at;  // offset of depth d's block in `blocks`
  std::vector<float> candidate;  // a depth's layout rebuilt for counting
  std::vector<float> chosen;     // the winning layout when it is neither 0 nor the deepest
  std::vector<double> energies;  // fixed-K search
};

SearchScratch& ThreadSearchScratch() {
  thread_local SearchScratch scratch;
  return scratch;
}

struct Extent {
  int w, h;
};
Extent BlockOf(const ColumnCodingParams& p, int d) {
  return {BlockExtent(p.width, d), BlockExtent(p.height, d)};
}

double WeightAt(std::span<const float> w, size_t i) { return w.empty() ? 1.0 : w[i]; }

// Σ (v_i·w_i)² over the coefficients a top-K selection leaves out: the n − K
// smallest weighted energies (ties have equal energy, so which of them TopK
// keeps does not change the sum).
double DroppedByTopK(std::span<const float> v, std::span<const float> w, int k,
                     std::vector<double>& energies) {
  energies.clear();
  for (size_t i = 0; i < v.size(); ++i) {
    const double m = double(v[i]) * WeightAt(w, i);
    if (m != 0) energies.push_back(m * m);
  }
  if (energies.size() <= static_cast<size_t>(k)) return 0;
  const auto cut = energies.end() - k;
  std::nth_element(energies.begin(), cut, energies.end());
  return std::accumulate(energies.begin(), cut, 0.0);
}

// The column transformed step by step to `deepest`. ForwardStep(s) only
// touches the top-left LL block of depth s, so the depth-d layout is the
// deepest one with that block put back as it was before step d: saving the
// blocks (4/3 of a column in all) lets any depth be rebuilt later.
class DepthStack {
 public:
  DepthStack(const ColumnCodingParams& p, std::span<const float> image, int deepest,
             SearchScratch& s)
      : p_(p), image_(image), deepest_(deepest), s_(s) {
    s_.work.assign(image.begin(), image.end());
    s_.blocks.clear();
    s_.block_at.assign(deepest + 1, 0);
  }

  // Applies step d−1, so that work() holds the depth-d layout, saving the
  // block that step overwrites. Call for d = 1, 2, …, deepest in order.
  void Step(int d) {
    const Extent b = BlockOf(p_, d - 1);
    s_.block_at[d - 1] = s_.blocks.size();
    if (d - 1 > 0) {  // depth 0's block is the image itself
      for (int y = 0; y < b.h; ++y) {
        const float* row = s_.work.data() + size_t(y) * p_.width;
        s_.blocks.insert(s_.blocks.end(), row, row + b.w);
      }
    }
    ForwardStep(p_.filter, s_.work, p_.width, p_.height, d - 1);
  }
  std::span<const float> work() const { return s_.work; }

  // The depth-d layout, valid until the next Rebuild into the same buffer.
  std::span<const float> Rebuild(int d, std::vector<float>& out) const {
    if (d == 0) return image_;
    if (d == deepest_) return s_.work;
    out.assign(s_.work.begin(), s_.work.end());
    const Extent b = BlockOf(p_, d);
    const float* block = s_.blocks.data() + s_.block_at[d];
    for (int y = 0; y < b.h; ++y)
      std::copy_n(block + size_t(y) * b.w, b.w, out.data() + size_t(y) * p_.width);
    return out;
  }

 private:
  const ColumnCodingParams& p_;
  std::span<const float> image_;
  int deepest_;
  SearchScratch& s_;
};

bool Beats(int count, int depth, int best_count, int best_depth) {
  // Ties go to the shallower depth (4D paper §4.2: fewer steps, same size).
  return count < best_count || (count == best_count && depth < best_depth);
}

// Adaptive with an energy budget: bounds at every depth settle most of the
// comparison; exact counts only where they leave a chance (see the header).
int SearchByCount(const ColumnCodingParams& p, const DepthStack& stack,
                  const std::vector<CountBounds>& bounds, double budget, SearchScratch& s) {
  std::vector<int> order(bounds.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return bounds[a].lower < bounds[b].lower; });
  // The most promising depth wins outright if even its upper bound beats
  // every other depth's lower bound.
  const int first = order[0];
  bool settled = true;
  for (int d : order) {
    if (d != first && !Beats(bounds[first].upper, first, bounds[d].lower, d)) settled = false;
  }
  if (settled) return first;
  int best_depth = -1, best_count = 0;
  for (int d : order) {
    if (best_depth >= 0 && !Beats(bounds[d].lower, d, best_count, best_depth)) continue;
    const int count =
        bounds[d].lower == bounds[d].upper
            ? bounds[d].lower
            : CountForBudget(stack.Rebuild(d, s.candidate), RankingWeights(p, d), budget);
    if (best_depth < 0 || Beats(count, d, best_count, best_depth)) {
      best_depth = d;
      best_count = count;
    }
  }
  return best_depth;
}

// Steps `stack` to every depth, with the count bounds of each. For the
// orthonormal filters (weights all ones) a step changes only its LL block,
// so one histogram follows the column down, updated block by block.
std::vector<CountBounds> StepWithBounds(const ColumnCodingParams& p, std::span<const float> image,
                                        int max_depth, double budget, DepthStack& stack) {
  std::vector<CountBounds> bounds(max_depth + 1);
  const bool unweighted = RankingWeights(p, max_depth).empty();
  EnergyHistogram running(budget);
  running.Add(image);
  bounds[0] = running.Bounds();
  for (int d = 1; d <= max_depth; ++d) {
    const Extent b = BlockOf(p, d - 1);
    auto block_rows = [&](auto update) {
      for (int y = 0; y < b.h; ++y) update(stack.work().subspan(size_t(y) * p.width, b.w));
    };
    // A block that is the whole column is cheaper counted afresh.
    const bool whole = size_t(b.w) * b.h == image.size();
    if (unweighted && !whole) block_rows([&](std::span<const float> row) { running.Remove(row); });
    stack.Step(d);
    if (unweighted) {
      if (whole) running = EnergyHistogram(budget);
      block_rows([&](std::span<const float> row) { running.Add(row); });
      bounds[d] = running.Bounds();
    } else {
      EnergyHistogram h(budget);
      h.Add(stack.work(), RankingWeights(p, d));
      bounds[d] = h.Bounds();
    }
  }
  return bounds;
}

// Adaptive with K terms per column: the depth dropping the least energy.
int SearchByDroppedEnergy(const ColumnCodingParams& p, const DepthStack& stack, int deepest,
                          SearchScratch& s) {
  int best_depth = 0;
  double best = 0;
  for (int d = 0; d <= deepest; ++d) {
    const double dropped = DroppedByTopK(stack.Rebuild(d, s.candidate), RankingWeights(p, d),
                                         p.column_terms, s.energies);
    if (d == 0 || dropped < best) best_depth = d, best = dropped;
  }
  return best_depth;
}

}  // namespace

DepthChoice ChooseDepth(const ColumnCodingParams& p, std::span<const float> image, double budget) {
  const int max_depth = MaxDepth(p.width, p.height);
  if (p.mode == ColumnMode::k2d) return {0, image};
  SearchScratch& s = ThreadSearchScratch();
  if (p.mode == ColumnMode::kFull) {
    s.work.assign(image.begin(), image.end());
    Forward2d(p.filter, s.work, p.width, p.height, max_depth);
    return {max_depth, s.work};
  }
  DepthStack stack(p, image, max_depth, s);
  int depth = 0;
  CountBounds depth0{0, std::numeric_limits<int>::max()};
  if (p.column_terms == 0) {
    const std::vector<CountBounds> bounds = StepWithBounds(p, image, max_depth, budget, stack);
    depth = SearchByCount(p, stack, bounds, budget, s);
    depth0 = bounds[0];
  } else {
    for (int d = 1; d <= max_depth; ++d) stack.Step(d);
    depth = SearchByDroppedEnergy(p, stack, max_depth, s);
  }
  return {depth, stack.Rebuild(depth, s.chosen), depth0};
}

}  // namespace wavebake
