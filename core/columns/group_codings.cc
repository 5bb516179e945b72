#include "core/columns/group_codings.h"

#include <algorithm>
#include <cmath>

#include "core/columns/coded_size.h"
#include "core/columns/quantizer.h"

namespace wavebake {
namespace {

// With --bits auto in matrix scope the step is one for the whole matrix,
// Δ² = 12·(target/2)²·E_ref / K̄: each coefficient a choice adds makes it
// finer for every kept coefficient of the matrix. Codes of ~log2(|v|/Δ) bits
// then grow by ½·log2(1 + 1/ΣK) each, ΣK·½·log2(1 + 1/ΣK) ≈ 1/(2 ln 2) bits
// in all per coefficient added. Charging that beside codes quantized at the
// fewest-count step prices every choice without quantizing it again.
constexpr double kSharedStepBits = 0.72134752044448170;  // 1/(2 ln 2)

// Which coding of each column a choice keeps: 1 the depth-0 one.
using Mask = std::vector<uint8_t>;

// A column's two codings quantized as FINALIZE would (dither included:
// without it, runs of equal values at depth 0 look like repeats that the
// dithered store does not have).
struct ColumnCodes {
  std::vector<int16_t> fewest, flat;
};

// FINALIZE's step for `coding` (core/columns/quantization_steps.h), with the
// matrix's mean count K̄ estimated by the group's under fewest coefficients.
double StepFor(const ColumnCodingParams& p, const CodedColumn& coding, double mean_count) {
  if (p.bits > 0) return coding.max_abs / MaxQuantCode(p.bits);
  const double k = p.scope == ErrorScope::kColumn ? double(coding.positions.size()) : mean_count;
  return k > 0 ? std::sqrt(12 * QuantizationBudget(p.target_error, coding.reference_energy) / k)
               : 0.0;
}

std::vector<int16_t> Codes(const ColumnCodingParams& p, const CodedColumn& coding,
                           double mean_count, uint64_t column) {
  thread_local std::vector<uint8_t> levels;  // uniform scaling: unused
  levels.assign(coding.values.size(), 0);
  std::vector<int16_t> codes(coding.values.size());
  QuantizeInto(coding.values, coding.positions, levels, LevelScaling::kUniform,
               float(StepFor(p, coding, mean_count)),
               p.bits > 0 ? MaxQuantCode(p.bits) : kMaxStoredCode, p.seed, column, codes);
  return codes;
}

double SharedStepBits(const ColumnCodingParams& p, double added) {
  return p.bits == 0 && p.scope == ErrorScope::kMatrix ? kSharedStepBits * added : 0.0;
}

// Every kSampleStride-th column of the matrix is compressed: the masks are
// compared on the same columns, and compressing all of them cost as much
// as coding them.
constexpr int kSampleStride = 4;

// The bytes of the sampled columns' arrays under `mask`, plus what the
// mask's extra coefficients cost the shared step. Columns with one coding
// only are the same under every mask and are left out.
double BytesOf(const ColumnCodingParams& p, std::span<const ColumnCodings> group, int first_column,
               std::span<const ColumnCodes> codes, const Mask& mask, CodedBytesFn bytes) {
  std::vector<uint32_t> positions;
  std::vector<int16_t> all_codes;
  double added = 0;
  for (size_t c = 0; c < group.size(); ++c) {
    if (group[c].flat.depth < 0) continue;
    if (mask[c])
      added += double(group[c].flat.positions.size()) - double(group[c].fewest.positions.size());
    if ((first_column + c) % kSampleStride != 0) continue;
    const CodedColumn& coding = mask[c] ? group[c].flat : group[c].fewest;
    const std::vector<int16_t>& q = mask[c] ? codes[c].flat : codes[c].fewest;
    positions.insert(positions.end(), coding.positions.begin(), coding.positions.end());
    all_codes.insert(all_codes.end(), q.begin(), q.end());
  }
  return kSampleStride * double(bytes(positions, all_codes)) + SharedStepBits(p, added) / 8;
}

}  // namespace

std::vector<uint8_t> ChooseGroupCodings(const ColumnCodingParams& p,
                                        std::span<const ColumnCodings> group, int first_column,
                                        CodedBytesFn bytes) {
  const size_t n = group.size();
  Mask fewest(n, 0), cheaper(n, 0);
  double mean_count = 0;
  for (const ColumnCodings& c : group) mean_count += double(c.fewest.positions.size());
  mean_count /= double(std::max<size_t>(n, 1));
  std::vector<ColumnCodes> codes(n);
  for (size_t c = 0; c < n; ++c) {
    if (group[c].flat.depth < 0) continue;
    codes[c].fewest = Codes(p, group[c].fewest, mean_count, first_column + c);
    codes[c].flat = Codes(p, group[c].flat, mean_count, first_column + c);
    // Each column's own estimate (core/columns/coded_size.h).
    const double added =
        double(group[c].flat.positions.size()) - double(group[c].fewest.positions.size());
    cheaper[c] = CodedBits(group[c].flat.positions, codes[c].flat) + SharedStepBits(p, added) <=
                 CodedBits(group[c].fewest.positions, codes[c].fewest);
  }
  if (cheaper == fewest) return fewest;
  return BytesOf(p, group, first_column, codes, cheaper, bytes) <
                 BytesOf(p, group, first_column, codes, fewest, bytes)
             ? cheaper
             : fewest;
}

}  // namespace wavebake
