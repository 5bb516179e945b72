#include "core/columns/group_codings.h"

#include <algorithm>
#include <cmath>

#include "core/columns/coded_size.h"
#include "core/columns/quantizer.h"

namespace wavebake {
namespace {

// With --bits auto in matrix scope the step is one for the whole matrix,
// Δ² = 12·(target/2)²·E_ref / K̄: each coefficient a column adds makes it
// finer for every kept coefficient of the matrix. Codes of ~log2(|v|/Δ) bits
// then grow by ½·log2(1 + 1/ΣK) each, ΣK·½·log2(1 + 1/ΣK) ≈ 1/(2 ln 2) bits
// in all per coefficient added, which a column's own estimate must count.
constexpr double kSharedStepBits = 0.72134752044448170;  // 1/(2 ln 2)

// Which coding of each column a choice keeps: 1 the depth-0 one.
using Mask = std::vector<uint8_t>;

const CodedColumn& Kept(const ColumnCodings& c, uint8_t flat) { return flat ? c.flat : c.fewest; }

double MeanCount(std::span<const ColumnCodings> group, const Mask& mask) {
  double sum = 0;
  for (size_t c = 0; c < group.size(); ++c) sum += double(Kept(group[c], mask[c]).positions.size());
  return group.empty() ? 0 : sum / double(group.size());
}

// FINALIZE's step for `coding` (core/columns/quantization_steps.h), `mean_count`
// standing for the matrix's mean count K̄.
double StepFor(const ColumnCodingParams& p, const CodedColumn& coding, double mean_count) {
  if (p.bits > 0) return coding.max_abs / MaxQuantCode(p.bits);
  const double k = p.scope == ErrorScope::kColumn ? double(coding.positions.size()) : mean_count;
  return k > 0 ? std::sqrt(12 * QuantizationBudget(p.target_error, coding.reference_energy) / k)
               : 0.0;
}

// The codes FINALIZE would write for `coding` with this step, dither
// included: without it, runs of equal values (a lit floor at depth 0) code
// as repeats that the dithered store does not have.
void AppendCodes(const ColumnCodingParams& p, const CodedColumn& coding, double step,
                 uint64_t column, std::vector<int16_t>& codes) {
  thread_local std::vector<uint8_t> levels;  // uniform scaling: unused
  levels.assign(coding.values.size(), 0);
  const size_t at = codes.size();
  codes.resize(at + coding.values.size());
  const int max_code = p.bits > 0 ? MaxQuantCode(p.bits) : kMaxStoredCode;
  QuantizeInto(coding.values, coding.positions, levels, LevelScaling::kUniform, float(step),
               max_code, p.seed, column, std::span(codes).subspan(at));
}

// The bytes of the group's arrays under `mask`, each column quantized with
// the step that the mask's own mean count gives.
size_t BytesOf(const ColumnCodingParams& p, std::span<const ColumnCodings> group, int first_column,
               const Mask& mask, CodedBytesFn bytes) {
  const double mean_count = MeanCount(group, mask);
  std::vector<uint32_t> positions;
  std::vector<int16_t> codes;
  for (size_t c = 0; c < group.size(); ++c) {
    const CodedColumn& coding = Kept(group[c], mask[c]);
    positions.insert(positions.end(), coding.positions.begin(), coding.positions.end());
    AppendCodes(p, coding, StepFor(p, coding, mean_count), first_column + c, codes);
  }
  return bytes(positions, codes);
}

// A column's own estimate (core/columns/coded_size.h) at the fewest-count
// step, plus the shared step's cost of its extra coefficients.
bool FlatLooksCheaper(const ColumnCodingParams& p, const ColumnCodings& column, uint64_t index,
                      double mean_count) {
  thread_local std::vector<int16_t> codes;
  auto bits = [&](const CodedColumn& coding) {
    codes.clear();
    AppendCodes(p, coding, StepFor(p, coding, mean_count), index, codes);
    return CodedBits(coding.positions, codes);
  };
  const bool shared = p.bits == 0 && p.scope == ErrorScope::kMatrix;
  const double added =
      double(column.flat.positions.size()) - double(column.fewest.positions.size());
  return bits(column.flat) + (shared ? kSharedStepBits * added : 0.0) <= bits(column.fewest);
}

}  // namespace

bool ComparesCodedSize(const ColumnCodingParams& p) {
  return p.mode == ColumnMode::kAdaptive && p.column_terms == 0 &&
         p.level_scaling == LevelScaling::kUniform;
}

std::vector<uint8_t> ChooseGroupCodings(const ColumnCodingParams& p,
                                        std::span<const ColumnCodings> group, int first_column,
                                        CodedBytesFn bytes) {
  const size_t n = group.size();
  Mask fewest(n, 0), flat(n, 0), cheaper(n, 0);
  const double mean_count = MeanCount(group, fewest);
  for (size_t c = 0; c < n; ++c) {
    if (group[c].flat.depth < 0) continue;
    flat[c] = 1;
    cheaper[c] = FlatLooksCheaper(p, group[c], first_column + c, mean_count);
  }
  if (flat == fewest) return fewest;  // no column has another coding
  const Mask* best = &fewest;
  size_t best_bytes = BytesOf(p, group, first_column, fewest, bytes);
  for (const Mask* choice : {&cheaper, &flat}) {
    if (*choice == *best) continue;
    const size_t b = BytesOf(p, group, first_column, *choice, bytes);
    if (b < best_bytes) best = choice, best_bytes = b;
  }
  return *best;
}

}  // namespace wavebake
