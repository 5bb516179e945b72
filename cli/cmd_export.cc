// `wavebake export STORE --format wavelet-tree --out DIR [--cut-off C |
// --target-error E] [--bits auto|B|B0,B1,...] [--level-weight W]
// [--jump-nodes J]`: a diffuse store's rows as GPU textures, Boulton
// §4.4–4.5 (driver/relight/tree_export.h; the format in DIR/header.json).
#include <cmath>
#include <cstdio>

#include "absl/strings/str_cat.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "driver/relight/tree_export.h"

namespace wavebake::cli {
namespace {

struct ExportFlags {
  std::string store, format, out;
  double cut_off = -1, target_error = -1, level_weight = 0;
  std::string bits = "auto";
  int jump_nodes = WaveletTreeOptions{}.jump_nodes;
};

void Run(const ExportFlags& f) {
  if (f.format != "wavelet-tree")
    Fail("export", "--format: '" + f.format + "' is not wavelet-tree", kExitBadInput);
  WaveletTreeOptions options;
  absl::StatusOr<std::vector<int>> bits = ParseCodeBits(f.bits);
  if (!bits.ok()) Fail("export", "--" + std::string(bits.status().message()), kExitBadInput);
  options.bits = *bits;
  options.level_weight = f.level_weight;
  options.jump_nodes = f.jump_nodes;
  if (f.cut_off >= 0) options.cut_off = f.cut_off;
  if (f.target_error >= 0) options.target_error = f.target_error;
  absl::StatusOr<nlohmann::json> h = driver::ExportWaveletTrees(f.store, f.out, options);
  if (!h.ok()) Fail("export", h.status());
  const nlohmann::json& s = (*h)["stats"];
  const double kept = s["nodes_kept"].get<double>() / std::max(1.0, s["nodes_total"].get<double>());
  std::printf(
      "%s: %lld trees, %.2f%% of nodes kept (%lld jumps), cut-off %.3g, rows' relative L2 "
      "error pruned %.4f, quantized %.4f, %.2f MB, %.1f s\n",
      f.out.c_str(), static_cast<long long>(s["trees"].get<int64_t>()), 100 * kept,
      static_cast<long long>(s["jumps"].get<int64_t>()), (*h)["settings"]["cut_off"].get<double>(),
      s["rel_error_pruned"].get<double>(), s["rel_error_quantized"].get<double>(),
      s["bytes"].get<double>() / 1e6, s["seconds"].get<double>());
}

}  // namespace

void AddExportCommand(CLI::App& app) {
  auto flags = std::make_shared<ExportFlags>();
  CLI::App* cmd = app.add_subcommand(
      "export", "a diffuse store's transport rows as GPU wavelet-tree textures (Boulton 4.4-4.5)");
  cmd->add_option("store", flags->store, "the store (OUT.wbk)")->required();
  cmd->add_option("--format", flags->format, "wavelet-tree")->required();
  cmd->add_option("--out", flags->out, "directory for header.json and the arrays")->required();
  auto* cut = cmd->add_option("--cut-off", flags->cut_off,
                              "absolute cut-off of a node's largest |coefficient| (Boulton 4.4)")
                  ->check(CLI::NonNegativeNumber);
  auto* target = cmd->add_option("--target-error", flags->target_error,
                                 absl::StrCat("relative L2 error of the pruned rows (default ",
                                              kDefaultTreeTargetError, ")"))
                     ->check(CLI::NonNegativeNumber);
  cut->excludes(target);
  cmd->add_option("--level-weight", flags->level_weight,
                  "importance weighting: a level-l node counts max|c| * 2^(-W l) against the "
                  "cut-off (0: Boulton's rule as written)")
      ->check(CLI::Range(-4.0, 8.0))
      ->capture_default_str();
  cmd->add_option("--bits", flags->bits,
                  "code bits per coefficient: auto (4 at the finest level, 5 and 6 at the next "
                  "two, 9 above), B at every level, or one per level, level 0 first (2..9)")
      ->capture_default_str();
  cmd->add_option("--jump-nodes", flags->jump_nodes,
                  "a node gets a jump record when at least this many kept nodes lie below it")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([flags] { Run(*flags); });
}

}  // namespace wavebake::cli
