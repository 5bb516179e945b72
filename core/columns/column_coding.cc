#include "core/columns/column_coding.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "core/columns/depth_search.h"
#include "core/columns/filled_depth.h"
#include "core/columns/nla.h"
#include "core/columns/zero_quads.h"
#include "core/wavelets/subband.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

double WeightOf(std::span<const float> w, size_t i) { return w.empty() ? 1.0 : w[i]; }

bool IsOrthonormal(WaveletFilter f) {
  return f == WaveletFilter::kHaar || f == WaveletFilter::kDaub4;
}

// The kept set at the chosen depth, increasing positions, and its dropped energy.
void Select(const ColumnCodingParams& p, std::span<const float> coeffs, std::span<const float> w,
            double budget, CodedColumn* out) {
  if (p.column_terms == 0) {
    Selection sel = SelectForBudget(coeffs, w, budget);
    out->positions = std::move(sel.kept);
    out->dropped_energy = sel.dropped_energy;
    return;
  }
  std::vector<uint32_t> top = TopK(coeffs, w, p.column_terms);
  std::erase_if(top, [&](uint32_t i) { return coeffs[i] == 0; });  // zeros are never kept
  std::sort(top.begin(), top.end());
  out->positions = std::move(top);
  double dropped = 0;
  auto next_kept = out->positions.begin();
  for (uint32_t i = 0; i < coeffs.size(); ++i) {
    if (next_kept != out->positions.end() && *next_kept == i) {
      ++next_kept;
      continue;
    }
    const double m = static_cast<double>(coeffs[i]) * WeightOf(w, i);
    dropped += m * m;
  }
  out->dropped_energy = dropped;
}

// Σ v² in index order (what the selection at depth 0 drops when it keeps
// nothing, to the bit) if it is ≤ `budget`. `energy` is the same sum in four
// interleaved partial sums, within n·2⁻⁵³ relative of it: far above the
// budget, the ordered sum is not needed.
std::optional<double> EnergyIfWithin(std::span<const float> image, double energy, double budget) {
  if (energy > budget * (1 + 1e-9)) return std::nullopt;
  double total = 0;
  for (float v : image) total += double{v} * v;
  if (total > budget) return std::nullopt;
  return total;
}

// What FINALIZE needs to pick this column's step (core/columns/quantizer.h):
// max_i |v_i/k_i| and Σ_i (k_i·w_i)²/12. Powers of two are exact (ldexp).
void QuantizationInputs(const ColumnCodingParams& p, std::span<const float> w, CodedColumn* c) {
  const std::vector<uint8_t>& level_map = SubbandLevels(p.width, p.height, c->depth);
  std::vector<uint8_t> levels(c->positions.size());
  for (size_t i = 0; i < levels.size(); ++i) levels[i] = level_map[c->positions[i]];
  c->max_abs = LevelScaledMax(c->values, levels, p.level_scaling);
  double unit = 0;
  for (size_t i = 0; i < levels.size(); ++i) {
    const double kw =
        std::ldexp(WeightOf(w, c->positions[i]), LevelExponent(p.level_scaling, levels[i]));
    unit += kw * kw / 12;
  }
  c->step_unit = unit;
}

}  // namespace

ColumnCodingParams MakeColumnCodingParams(const BakeParams& params, int width, int height,
                                          double matrix_energy) {
  return {.width = width,
          .height = height,
          .filter = params.column_filter,
          .mode = params.column_mode,
          .target_error = params.target_error,
          .scope = params.error_scope,
          .column_terms = params.column_terms,
          .matrix_energy = matrix_energy,
          .level_scaling = params.level_scaling,
          .bits = params.bits,
          .seed = params.seed};
}

std::span<const float> RankingWeights(const ColumnCodingParams& p, int depth) {
  if (IsOrthonormal(p.filter) || depth == 0) return {};
  return SynthesisNormsRef(p.filter, p.width, p.height, depth);
}

const std::vector<uint8_t>& SubbandLevels(int width, int height, int depth) {
  using Key = std::tuple<int, int, int>;
  thread_local std::map<Key, std::vector<uint8_t>> cache;
  std::vector<uint8_t>& levels = cache[Key{width, height, depth}];
  if (levels.empty()) {
    levels.resize(size_t(width) * height);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        levels[size_t(y) * width + x] = uint8_t(SubbandAt(x, y, width, height, depth).level);
  }
  return levels;
}

namespace {

// A depth-0 alternative keeping more than twice the coefficients is not
// coded: a depth-0 coefficient would have to cost under half the bits of a
// deep one, and compressing each column of the bunny's stores alone (targets
// 0.003–0.03), no column whose depth-0 coding was the smaller kept more than
// 1.77 times as many. On camera scenes, where depth 0 keeps 3–4 times as
// many, this skips nearly every alternative.
constexpr size_t kFlatCountLimit = 2;

// The selection in `out` (positions, dropped energy) at `depth` completed:
// values, the energy left out before coding, quantization inputs.
void Complete(const ColumnCodingParams& p, int depth, std::span<const float> coefficients,
              double left_out, CodedColumn* out) {
  out->depth = depth;
  const std::span<const float> w = RankingWeights(p, depth);
  out->dropped_energy += left_out;
  out->values.reserve(out->positions.size());
  for (uint32_t pos : out->positions) out->values.push_back(coefficients[pos]);
  QuantizationInputs(p, w, out);
  out->min_bits = MinBitsFor(out->max_abs, out->step_unit,
                             QuantizationBudget(p.target_error, out->reference_energy));
}

// What every coding of a column starts with: its energy, its reference and
// its budget. True when that settles it: an empty column, or one whose whole
// energy fits the budget, keeps nothing at any depth, so no depth is tried
// (ties: the shallower; `full` records its one depth).
bool KeepsNothing(const ColumnCodingParams& p, std::span<const float> image, double left_out,
                  CodedColumn* out, double* budget) {
  out->energy = SumOfSquares(image.data(), image.size());
  out->reference_energy = p.scope == ErrorScope::kColumn ? out->energy : p.matrix_energy;
  out->dropped_energy = left_out;
  const int none_depth = p.mode == ColumnMode::kFull ? MaxDepth(p.width, p.height) : 0;
  if (out->energy == 0) {  // an empty column keeps nothing (DESIGN.md §1)
    out->depth = none_depth;
    return true;
  }
  *budget = std::max(0.0, p.target_error * p.target_error * out->reference_energy - left_out);
  if (p.column_terms != 0) return false;
  const std::optional<double> dropped = EnergyIfWithin(image, out->energy, *budget);
  if (!dropped) return false;
  out->depth = none_depth;
  out->dropped_energy += *dropped;
  return true;
}

}  // namespace

void CodeColumn(const ColumnCodingParams& p, std::span<const float> image, CodedColumn* out,
                double left_out, CodedColumn* flat) {
  *out = CodedColumn{};
  if (flat != nullptr) *flat = NoCoding();
  double budget = 0;
  if (KeepsNothing(p, image, left_out, out, &budget)) return;
  const DepthChoice choice = ChooseFilledDepth(p, image, budget);
  Select(p, choice.coefficients, RankingWeights(p, choice.depth), budget, out);
  const size_t flat_limit = kFlatCountLimit * out->positions.size();
  if (flat != nullptr && choice.depth != 0 && ComparesCodedSize(p) &&
      static_cast<size_t>(choice.depth0.lower) <= flat_limit) {
    // Depth 0 keeps cells, as `2d` does: no fill, no weights. The search's
    // bounds on its count spare most camera columns this selection.
    Selection cells = SelectForBudget(image, {}, budget);
    if (cells.kept.size() <= flat_limit) {
      flat->energy = out->energy;
      flat->reference_energy = out->reference_energy;
      flat->positions = std::move(cells.kept);
      flat->dropped_energy = cells.dropped_energy;
      Complete(p, 0, image, left_out, flat);
    }
  }
  Complete(p, choice.depth, choice.coefficients, left_out, out);
}

void CodeColumnAtDepth(const ColumnCodingParams& p, std::span<const float> image, int depth,
                       CodedColumn* out, double left_out) {
  *out = CodedColumn{};
  double budget = 0;
  if (KeepsNothing(p, image, left_out, out, &budget)) return;
  const DepthChoice at = FilledAtDepth(p, image, depth);
  Select(p, at.coefficients, RankingWeights(p, depth), budget, out);
  Complete(p, depth, at.coefficients, left_out, out);
}

bool ComparesCodedSize(const ColumnCodingParams& p) {
  return p.mode == ColumnMode::kAdaptive && p.column_terms == 0 &&
         p.level_scaling == LevelScaling::kUniform;
}

double QuantizationBudget(double target_error, double reference_energy) {
  return 0.25 * target_error * target_error * reference_energy;
}

double QuantizationEnergy(double max_abs, double step_unit, int bits) {
  // The step as Quantize will store it (a float rounded up).
  const double step = StepForMax(max_abs, MaxQuantCode(bits));
  return step * step * step_unit;
}

int MinBitsFor(double max_abs, double step_unit, double allowed) {
  for (int b = 2; b < 16; ++b) {
    if (QuantizationEnergy(max_abs, step_unit, b) <= allowed) return b;
  }
  return 16;
}

}  // namespace wavebake
