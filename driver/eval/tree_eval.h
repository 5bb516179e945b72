#pragma once
// `wavebake eval STORE --env ENV --tree-cut-off C…`: the wavelet-tree
// export's relighting error against the independent reference, beside the
// store's own (the CPU relighter, which mode=4d of `wavebake view` equals
// within float rounding), the reference traced once for all settings.
// The trees are relit by their independent reader (runtime/gpu/
// wavelet_tree_reader.h: the frame the shader's is tested against) under
// the same wavelet lights as the store.
#include <filesystem>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "nlohmann/json.hpp"
#include "runtime/gpu/wavelet_tree.h"
#include "runtime/reference/eval.h"

namespace wavebake::driver {

struct TreeEvalRow {
  WaveletTreeOptions asked;
  double cut_off = 0;          // the one used
  std::vector<int> code_bits;  // per level, as used
  int64_t bytes = 0, trees = 0, nodes_kept = 0, nodes_total = 0, jumps = 0;
  double rel_error_pruned = 0;     // of the rows' energy
  double rel_error_quantized = 0;  // the kept coefficients' rounding, of the rows' energy
  ErrorStats error;                // against the reference
};

struct TreeEvalReport {
  EvalReport store;  // the store relit by the CPU relighter (no dense T)
  std::vector<TreeEvalRow> trees;
};

// Errors: as Evaluate's and StoreWaveletTrees'.
absl::StatusOr<TreeEvalReport> EvaluateTrees(const std::filesystem::path& store,
                                             std::string_view env_spec, int terms,
                                             const EvalOptions& options,
                                             const std::vector<WaveletTreeOptions>& settings);

// EvalReportJson of the store plus "trees": [{"cut_off", "target_error"
// (null when a cut-off was given), "level_weight", "code_bits", "bytes",
// "trees", "nodes_kept", "nodes_total", "jumps", "rel_error_pruned",
// "rel_error_quantized", "rel_rms", "max_abs", "psnr"}].
nlohmann::json TreeEvalJson(const TreeEvalReport& r);
std::string TreeEvalText(const TreeEvalReport& r);

}  // namespace wavebake::driver
