#include "core/columns/filled_depth.h"

#include <vector>

#include "core/columns/nla.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

struct FilledScratch {
  std::vector<float> filled;     // the image with its uncovered cells filled
  std::vector<float> candidate;  // one depth's layout, free coefficients zeroed
  std::vector<float> chosen;     // the winner
};

FilledScratch& ThreadFilledScratch() {
  thread_local FilledScratch scratch;
  return scratch;
}

// Haar, energy budget: every depth counted with its free coefficients zeroed; ties go to the
// shallower depth (4D paper §4.2).
DepthChoice SearchHaar(const ColumnCodingParams& p, std::span<const float> image, double budget,
                       FilledScratch& s) {
  int best_depth = 0;
  const int depth0_count = CountForBudget(image, {}, budget);
  int best_count = depth0_count;
  const int max_depth = MaxDepth(p.width, p.height);
  for (int d = 1; d <= max_depth; ++d) {
    ForwardStep(p.filter, s.filled, p.width, p.height, d - 1);  // filled now holds depth d
    s.candidate.assign(s.filled.begin(), s.filled.end());
    p.filler->ZeroUncoveredCoefficients(s.candidate, d);
    const int count = CountForBudget(s.candidate, {}, budget);
    if (count < best_count) {
      best_count = count;
      best_depth = d;
      s.chosen.swap(s.candidate);
    }
  }
  if (best_depth == 0) return {0, image, {depth0_count, depth0_count}};
  return {best_depth, s.chosen, {depth0_count, depth0_count}};
}

}  // namespace

DepthChoice ChooseFilledDepth(const ColumnCodingParams& p, std::span<const float> image,
                              double budget) {
  if (p.filler == nullptr || p.mode == ColumnMode::k2d) return ChooseDepth(p, image, budget);
  FilledScratch& s = ThreadFilledScratch();
  s.filled.assign(image.begin(), image.end());
  p.filler->Fill(s.filled);
  const bool haar = p.filter == WaveletFilter::kHaar;
  if (haar && p.mode == ColumnMode::kAdaptive && p.column_terms == 0)
    return SearchHaar(p, image, budget, s);
  DepthChoice choice = ChooseDepth(p, s.filled, budget);
  if (choice.depth == 0) return {0, image};
  if (haar) {
    s.chosen.assign(choice.coefficients.begin(), choice.coefficients.end());
    p.filler->ZeroUncoveredCoefficients(s.chosen, choice.depth);
    choice.coefficients = s.chosen;
  }
  if (p.mode == ColumnMode::kAdaptive && p.column_terms == 0) {
    const int depth0_count = CountForBudget(image, {}, budget);
    if (depth0_count <=
        CountForBudget(choice.coefficients, RankingWeights(p, choice.depth), budget))
      return {0, image, {depth0_count, depth0_count}};  // ties: the shallower
    choice.depth0 = {depth0_count, depth0_count};
    return choice;
  }
  choice.depth0 = DepthChoice{}.depth0;  // they were the filled image's
  return choice;
}

DepthChoice FilledAtDepth(const ColumnCodingParams& p, std::span<const float> image, int depth) {
  if (depth == 0) return {0, image};
  FilledScratch& s = ThreadFilledScratch();
  s.chosen.assign(image.begin(), image.end());
  if (p.filler != nullptr) p.filler->Fill(s.chosen);
  Forward2d(p.filter, s.chosen, p.width, p.height, depth);
  if (p.filler != nullptr && p.filter == WaveletFilter::kHaar)
    p.filler->ZeroUncoveredCoefficients(s.chosen, depth);
  return {depth, s.chosen};
}

}  // namespace wavebake
