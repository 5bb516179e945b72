#pragma once
// The "stats" FINALIZE records in a store's root .zattrs (DESIGN.md §3):
// sizes, the depth histograms (overall and by row-transform level, the 4D
// paper's Fig. 8) and the achieved per-column error.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

namespace wavebake {

// One finished column as FINALIZE saw it.
struct ColumnOutcome {
  int column = 0;  // m = face*N*N + y*N + x
  int depth = 0;
  uint32_t kept = 0;
  double energy = 0;               // Σ of its squared staged values
  double reference_energy = 0;     // E_ref of its error scope
  double dropped_energy = 0;       // selection: Σ (c_i·w_i)² dropped
  double quantization_energy = 0;  // achieved: Σ ((ĉ_i − c_i)·w_i)² over kept coefficients
  int min_bits = 2;  // its own need with max normalization (core/columns/column_coding.h)
  int bits = 0;      // what its largest code needs (0: no codes)
};

class StoreStats {
 public:
  StoreStats(int light_res, int max_depth);
  void Add(const ColumnOutcome& c);
  // nnz, column counts, depth histograms, error summary. The error of a
  // column is sqrt(dropped + quantization) / sqrt(E_ref); mean and max are
  // over the columns with energy (an empty column keeps nothing and has none).
  nlohmann::json ToJson() const;
  int max_bits() const { return max_bits_; }

 private:
  int light_res_;
  std::vector<int64_t> depth_histogram_;                                      // [depth]
  std::vector<std::vector<int64_t>> depth_by_row_level_;                      // [row level][depth]
  std::vector<int64_t> bits_needed_histogram_ = std::vector<int64_t>(17, 0);  // [bits], 2..16 used
  std::vector<int64_t> column_bits_histogram_ = std::vector<int64_t>(17, 0);  // [bits], 0 = empty
  int max_bits_ = 0;
  int64_t nnz_ = 0, columns_ = 0, nonzero_columns_ = 0;
  double error_sum_ = 0, error_max_ = 0;
  double dropped_sum_ = 0, quantization_sum_ = 0, energy_sum_ = 0;
};

}  // namespace wavebake
