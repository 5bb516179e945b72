#include "cli/bake_flags.h"

#include <charconv>

#include "absl/strings/str_cat.h"
#include "core/bake_params_io.h"

namespace wavebake::cli {

void AddBakeFlags(CLI::App& cmd, BakeFlags& f) {
  cmd.add_option("--light-res", f.light_res,
                 "cubemap texels per face edge N (power of two, 8..256)")
      ->capture_default_str();
  cmd.add_option("--layout", f.layout, "spatial layout: camera[:WxH] | grid | hilbert:WxH")
      ->capture_default_str();
  cmd.add_option("--supersample", f.supersample, "jittered directions per texel K")
      ->capture_default_str();
  cmd.add_option("--row-filter", f.row_filter, "row transform: haar | daub4")
      ->capture_default_str();
  cmd.add_option("--column-mode", f.column_mode, "column transform depth: adaptive | full | 2d")
      ->capture_default_str();
  cmd.add_option("--column-filter", f.column_filter, "column filter: haar | legall53 | cdf97")
      ->capture_default_str();
  cmd.add_option(
         "--target-error", f.target_error,
         "relative RMS error budget of the stored columns (DESIGN.md §1, see --error-scope)")
      ->capture_default_str();
  cmd.add_option("--error-scope", f.error_scope,
                 "matrix: budget relative to the mean column energy; column: to each column's own")
      ->capture_default_str();
  cmd.add_option("--column-terms", f.column_terms,
                 "keep exactly K coefficients per column instead of --target-error");
  cmd.add_option(
         "--bits", f.bits,
         "quantization bits 2..16 (each column's max to the largest code), or auto (the error "
         "budget's quantization half)")
      ->capture_default_str();
  cmd.add_option("--level-scaling", f.level_scaling,
                 "uniform: one step per column (auto: one matrix-wide step); paper: values of "
                 "level l times 2^l first (4D paper §4.3)")
      ->capture_default_str();
  cmd.add_option("--seed", f.seed, "job seed (jitter and dither)")->capture_default_str();
  cmd.add_option("--refine", f.refine,
                 "on: trace only where visibility changes (coarse probes, refined along "
                 "silhouettes; fully visible texels get their exact integral); off: brute force, "
                 "K rays in every texel")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd.add_flag("--keep-staging", f.keep_staging,
               "leave the staging arrays (row-transformed T, transposed) in the store");
  cmd.add_option("--tile-size", f.tile_size,
                 "spatial tile edge of one BAKE_TILE task (power of two)")
      ->capture_default_str();
  cmd.add_option("--column-group", f.column_group, "columns per TRANSFORM_COLUMNS task")
      ->capture_default_str();
}

absl::StatusOr<BakeParams> ToParams(const BakeFlags& f) {
  BakeParams p;
  p.light_res = f.light_res;
  p.layout = f.layout;
  p.supersample = f.supersample;
  auto row = ParseWaveletFilter(f.row_filter);
  if (!row.ok()) return absl::InvalidArgumentError(absl::StrCat("row_", row.status().message()));
  p.row_filter = *row;
  auto mode = ParseColumnMode(f.column_mode);
  if (!mode.ok()) return mode.status();
  p.column_mode = *mode;
  auto col = ParseWaveletFilter(f.column_filter);
  if (!col.ok()) return absl::InvalidArgumentError(absl::StrCat("column_", col.status().message()));
  p.column_filter = *col;
  auto scope = ParseErrorScope(f.error_scope);
  if (!scope.ok()) return scope.status();
  p.error_scope = *scope;
  auto scaling = ParseLevelScaling(f.level_scaling);
  if (!scaling.ok()) return scaling.status();
  p.level_scaling = *scaling;
  p.target_error = f.target_error;
  p.column_terms = f.column_terms;
  p.seed = f.seed;
  p.keep_staging = f.keep_staging;
  p.refine = f.refine == "on";
  p.tile_size = f.tile_size;
  p.column_group = f.column_group;
  if (f.bits != "auto") {
    const char* end = f.bits.data() + f.bits.size();
    auto [ptr, ec] = std::from_chars(f.bits.data(), end, p.bits);
    if (ec != std::errc() || ptr != end || p.bits == 0)
      return absl::InvalidArgumentError(absl::StrCat("bits: '", f.bits, "' is not 2..16 or auto"));
  }
  if (absl::Status s = ValidateBakeParams(p); !s.ok()) return s;
  return p;
}

}  // namespace wavebake::cli
