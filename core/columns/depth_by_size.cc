#include "core/columns/depth_by_size.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/columns/coded_size.h"

namespace wavebake {
namespace {

double MaxAbs(std::span<const float> v, std::span<const uint32_t> kept) {
  double m = 0;
  for (uint32_t i : kept) m = std::max(m, std::fabs(double{v[i]}));
  return m;
}

double EstimatedStep(const ColumnCodingParams& p, double reference_energy, std::span<const float> v,
                     std::span<const uint32_t> kept, size_t deep_count) {
  if (p.bits > 0) return MaxAbs(v, kept) / MaxQuantCode(p.bits);
  return std::sqrt(12 * QuantizationBudget(p.target_error, reference_energy) / deep_count);
}

double Bits(std::span<const float> v, std::span<const uint32_t> kept, double step) {
  thread_local std::vector<int16_t> codes;
  codes.resize(kept.size());
  for (size_t k = 0; k < kept.size(); ++k) {
    const double q = step > 0 ? std::round(v[kept[k]] / step) : 0.0;
    codes[k] = static_cast<int16_t>(std::clamp(q, -double{kMaxStoredCode}, double{kMaxStoredCode}));
  }
  return CodedBits(kept, codes);
}

}  // namespace

bool ComparesCodedSize(const ColumnCodingParams& p) {
  return p.depth_by_size && p.mode == ColumnMode::kAdaptive && p.column_terms == 0 &&
         p.level_scaling == LevelScaling::kUniform;
}

bool DepthZeroCodesSmaller(const ColumnCodingParams& p, double reference_energy,
                           std::span<const float> image, std::span<const uint32_t> flat_kept,
                           std::span<const float> deep, std::span<const uint32_t> deep_kept) {
  const size_t n = std::max<size_t>(1, deep_kept.size());
  const double flat_bits =
      Bits(image, flat_kept, EstimatedStep(p, reference_energy, image, flat_kept, n));
  const double deep_bits =
      Bits(deep, deep_kept, EstimatedStep(p, reference_energy, deep, deep_kept, n));
  return flat_bits <= deep_bits;
}

}  // namespace wavebake
