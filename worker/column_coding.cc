#include "worker/column_coding.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/nla.h"
#include "core/subband.h"
#include "core/wavelet2d.h"

namespace wavebake {
namespace {

// Reused by every column a thread codes: the adaptive search transforms each
// column at every depth, and allocating per column would cost more than the
// search (the brief of issue "Column stage").
struct ColumnScratch {
  std::vector<float> work;       // the column, transformed step by step
  std::vector<float> best;       // the best depth seen so far (adaptive only)
  std::vector<double> energies;  // weighted squared magnitudes (fixed-K search)
};

ColumnScratch& ThreadColumnScratch() {
  thread_local ColumnScratch scratch;
  return scratch;
}

bool IsOrthonormal(WaveletFilter f) {
  return f == WaveletFilter::kHaar || f == WaveletFilter::kDaub4;
}

// The ranking weights of a depth-d layout; empty means all ones (core/nla.h),
// which spares the multiply for the orthonormal filters.
std::span<const float> Weights(const ColumnCodingParams& p, int depth) {
  if (IsOrthonormal(p.filter) || depth == 0) return {};
  return SynthesisNormsRef(p.filter, p.width, p.height, depth);
}

double WeightOf(std::span<const float> w, size_t i) { return w.empty() ? 1.0 : w[i]; }

// Σ (v_i·w_i)² over the coefficients a top-K selection leaves out: the
// n − K smallest weighted energies (ties have equal energy, so which of them
// TopK keeps does not change the sum).
double DroppedByTopK(std::span<const float> v, std::span<const float> w, int k,
                     std::vector<double>& energies) {
  energies.clear();
  for (size_t i = 0; i < v.size(); ++i) {
    const double m = static_cast<double>(v[i]) * WeightOf(w, i);
    if (m != 0) energies.push_back(m * m);
  }
  if (energies.size() <= static_cast<size_t>(k)) return 0;
  const auto cut = energies.end() - k;
  std::nth_element(energies.begin(), cut, energies.end());
  return std::accumulate(energies.begin(), cut, 0.0);
}

// What the depth search minimizes: kept coefficients for the budget, or the
// dropped energy for a fixed K (DESIGN.md §1).
double SearchCost(const ColumnCodingParams& p, std::span<const float> coeffs,
                  std::span<const float> w, double budget, ColumnScratch& scratch) {
  if (p.column_terms > 0) return DroppedByTopK(coeffs, w, p.column_terms, scratch.energies);
  return CountForBudget(coeffs, w, budget);
}

// Transforms scratch.work to every depth the mode allows and returns the
// winning depth; its coefficients are left in the returned span.
std::span<const float> SearchDepth(const ColumnCodingParams& p, double budget,
                                   ColumnScratch& scratch, int* depth) {
  const int max_depth = MaxDepth(p.width, p.height);
  const int first = p.mode == ColumnMode::kFull ? max_depth : 0;
  const int last = p.mode == ColumnMode::k2d ? 0 : max_depth;
  std::span<float> work(scratch.work);
  int best_depth = -1;
  double best_cost = 0;
  for (int d = 0; d <= last; ++d) {
    if (d > 0) ForwardStep(p.filter, work, p.width, p.height, d - 1);
    if (d < first) continue;
    const double cost = SearchCost(p, work, Weights(p, d), budget, scratch);
    // Ties keep the shallower depth (4D paper §4.2: fewer steps for the same size).
    if (best_depth >= 0 && !(cost < best_cost)) continue;
    best_depth = d;
    best_cost = cost;
    if (first == last) break;
    scratch.best.assign(work.begin(), work.end());
    // Keeping nothing cannot be beaten, and deeper ties lose.
    if (p.column_terms == 0 && cost == 0) break;
  }
  *depth = best_depth;
  return first == last ? std::span<const float>(scratch.work)
                       : std::span<const float>(scratch.best);
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

// Σ_i (scale·2^−l_i·w_i)²/12 with scale = max_i |v_i·2^l_i| rounded up to
// float exactly as core/quantizer.h Quantize stores it.
double QuantizationUnit(const ColumnCodingParams& p, std::span<const float> w,
                        const CodedColumn& c) {
  auto level = [&](uint32_t pos) {
    return SubbandAt(static_cast<int>(pos % p.width), static_cast<int>(pos / p.width), p.width,
                     p.height, c.depth)
        .level;
  };
  double scale = 0;
  for (size_t i = 0; i < c.positions.size(); ++i)
    scale = std::max(scale, std::fabs(std::ldexp(double{c.values[i]}, level(c.positions[i]))));
  float stored = static_cast<float>(scale);
  if (stored < scale) stored = std::nextafter(stored, INFINITY);
  double unit = 0;
  for (uint32_t pos : c.positions) {
    const double step = std::ldexp(double{stored}, -level(pos)) * WeightOf(w, pos);
    unit += step * step / 12;
  }
  return unit;
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
          .matrix_energy = matrix_energy};
}

void CodeColumn(const ColumnCodingParams& p, std::span<const float> image, CodedColumn* out) {
  *out = CodedColumn{};
  for (float v : image) out->energy += static_cast<double>(v) * v;
  out->reference_energy = p.scope == ErrorScope::kColumn ? out->energy : p.matrix_energy;
  if (out->energy == 0) {  // an empty column keeps nothing (DESIGN.md §1)
    out->depth = p.mode == ColumnMode::kFull ? MaxDepth(p.width, p.height) : 0;
    return;
  }
  const double budget = p.target_error * p.target_error * out->reference_energy;
  ColumnScratch& scratch = ThreadColumnScratch();
  scratch.work.assign(image.begin(), image.end());
  const std::span<const float> coeffs = SearchDepth(p, budget, scratch, &out->depth);
  const std::span<const float> w = Weights(p, out->depth);
  Select(p, coeffs, w, budget, out);
  out->values.reserve(out->positions.size());
  for (uint32_t pos : out->positions) out->values.push_back(coeffs[pos]);
  out->quantization_unit = QuantizationUnit(p, w, *out);
  out->min_bits = MinBitsFor(out->quantization_unit, p.target_error, out->reference_energy);
}

int MaxQuantCode(int bits) { return (1 << (bits - 1)) - 1; }

double QuantizationEnergy(double quantization_unit, int bits) {
  const double q = MaxQuantCode(bits);
  return quantization_unit / (q * q);
}

int MinBitsFor(double quantization_unit, double target_error, double reference_energy) {
  const double allowed = 0.25 * target_error * target_error * reference_energy;
  for (int b = 2; b < 16; ++b) {
    if (QuantizationEnergy(quantization_unit, b) <= allowed) return b;
  }
  return 16;
}

}  // namespace wavebake
