#include "worker/columns/store_stats.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/wavelets/subband.h"

namespace wavebake {

StoreStats::StoreStats(int light_res, int max_depth)
    : light_res_(light_res),
      depth_histogram_(max_depth + 1, 0),
      // Row levels of an N×N face: 0 (scaling) .. log2(N) (finest details).
      depth_by_row_level_(std::bit_width(static_cast<unsigned>(light_res)),
                          std::vector<int64_t>(max_depth + 1, 0)) {}

void StoreStats::Add(const ColumnOutcome& c) {
  const int texel = c.column % (light_res_ * light_res_);
  const int row_level = RowLevel(texel % light_res_, texel / light_res_);
  ++depth_histogram_.at(c.depth);
  ++depth_by_row_level_.at(row_level).at(c.depth);
  ++bits_needed_histogram_.at(c.min_bits);
  ++column_bits_histogram_.at(c.bits);
  max_bits_ = std::max(max_bits_, c.bits);
  ++columns_;
  nnz_ += c.kept;
  dropped_sum_ += c.dropped_energy;
  quantization_sum_ += c.quantization_energy;
  energy_sum_ += c.energy;
  if (c.energy == 0) return;
  ++nonzero_columns_;
  const double error =
      c.reference_energy > 0
          ? std::sqrt((c.dropped_energy + c.quantization_energy) / c.reference_energy)
          : 0.0;
  error_sum_ += error;
  error_max_ = std::max(error_max_, error);
}

nlohmann::json StoreStats::ToJson() const {
  nlohmann::json mean_depth = nlohmann::json::array();
  for (const std::vector<int64_t>& h : depth_by_row_level_) {
    int64_t n = 0, sum = 0;
    for (size_t d = 0; d < h.size(); ++d) {
      n += h[d];
      sum += h[d] * static_cast<int64_t>(d);
    }
    mean_depth.push_back(n > 0 ? double(sum) / double(n) : 0.0);
  }
  return {
      {"nnz", nnz_},
      {"columns", columns_},
      {"nonzero_columns", nonzero_columns_},
      {"kept_per_column", columns_ > 0 ? double(nnz_) / double(columns_) : 0.0},
      {"depth_histogram", depth_histogram_},
      {"depth_by_row_level", depth_by_row_level_},
      {"mean_depth_by_row_level", mean_depth},
      // How many columns need b bits (index b) on their own with max
      // normalization (the paper's rule).
      {"bits_needed_histogram", bits_needed_histogram_},
      // How many columns' largest code needs b bits (index b; 0: no codes):
      // what a per-column bit width would cost with the steps used.
      {"column_bits_histogram", column_bits_histogram_},
      {"column_error",
       {{"mean", nonzero_columns_ > 0 ? error_sum_ / double(nonzero_columns_) : 0.0},
        {"max", error_max_}}},
      // The whole matrix: sqrt(Σ dropped + quantization energy / Σ energy).
      {"matrix_rel_rms",
       energy_sum_ > 0 ? std::sqrt((dropped_sum_ + quantization_sum_) / energy_sum_) : 0.0},
      {"dropped_energy", dropped_sum_},
      {"quantization_energy", quantization_sum_},
      {"energy", energy_sum_},
  };
}

}  // namespace wavebake
