#pragma once
// Which transform depth a column gets (DESIGN.md §1 "Column transform"; 4D
// paper §4.2 "optimal transform depth"): `2d` keeps depth 0, `full` the
// maximum, `adaptive` tries every depth and keeps the one needing the fewest
// coefficients for the column's energy budget (ties: the shallower), or, with
// a fixed K per column, the one dropping the least energy.
#include <limits>
#include <span>

#include "core/columns/column_coding.h"
#include "core/columns/count_bounds.h"

namespace wavebake {

struct DepthChoice {
  int depth = 0;
  // The column's coefficients at `depth` (Mallat layout). A view of `image`
  // or of per-thread scratch: valid until the next ChooseDepth on this thread.
  std::span<const float> coefficients;
  // Bounds on CountForBudget of the image itself (depth 0) where the search
  // learned them, else [0, max]: a caller weighing depth 0 against the
  // choice may be spared a count.
  CountBounds depth0{0, std::numeric_limits<int>::max()};
};

// `budget` is the dropped-energy budget target²·E_ref (unused with K terms).
//
// The adaptive budget search does not count every depth exactly: at each
// depth, the coefficients whose own weighted energy exceeds the budget must
// be kept whatever else is dropped, so their number is a lower bound on that
// depth's count. Exact counts (core/columns/nla.h CountForBudget) are taken in order
// of increasing bound, and a depth whose bound cannot beat the best count so
// far is skipped — the same choice as counting every depth, at a fraction of
// the cost.
DepthChoice ChooseDepth(const ColumnCodingParams& p, std::span<const float> image, double budget);

}  // namespace wavebake
