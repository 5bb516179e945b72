#include "cli/bake_flags.h"

#include <charconv>

#include "absl/strings/str_cat.h"
#include "core/bake_params_io.h"
#include "core/layout.h"

namespace wavebake::cli {
namespace {

// A parsed name into `out`; the error keeps the parser's field name, with
// `prefix` for the two filters (row_filter, column_filter).
template <typename T>
absl::Status Set(absl::StatusOr<T> parsed, T& out, const char* prefix = "") {
  if (!parsed.ok())
    return absl::InvalidArgumentError(absl::StrCat(prefix, parsed.status().message()));
  out = *parsed;
  return absl::OkStatus();
}

}  // namespace

void AddBakeFlags(CLI::App& cmd, BakeFlags& f) {
  BakeParams& p = f.params;
  cmd.add_option("--light-res", p.light_res,
                 "cubemap texels per face edge N (power of two, 8..256)")
      ->capture_default_str();
  cmd.add_option("--light-domain", f.light_domain,
                 "cube | plane:S[:AXIS]: one face of size S (3..10) aligned with a light plane "
                 "normal to AXIS (default +Y), for --area-light")
      ->capture_default_str();
  cmd.add_option("--layout", p.layout,
                 "spatial layout: camera[:WxH] | grid | hilbert:WxH | uv[:WxH] | uv1[:WxH] "
                 "(lightmap texels of UV channel 0 or 1, default 256x256)")
      ->capture_default_str();
  cmd.add_flag("--allow-uv-overlap", f.allow_uv_overlap,
               "uv layouts: bake an atlas whose charts overlap (each texel then takes its "
               "nearest triangle)");
  cmd.add_option("--supersample", p.supersample, "jittered directions per texel K")
      ->capture_default_str();
  cmd.add_option("--row-filter", f.row_filter, "row transform: haar | daub4")
      ->capture_default_str();
  cmd.add_option("--column-mode", f.column_mode, "column transform depth: adaptive | full | 2d")
      ->capture_default_str();
  cmd.add_option("--column-filter", f.column_filter, "column filter: haar | legall53 | cdf97")
      ->capture_default_str();
  cmd.add_option(
         "--target-error", p.target_error,
         "relative RMS error budget of the stored columns (DESIGN.md §1, see --error-scope)")
      ->capture_default_str();
  cmd.add_option("--error-scope", f.error_scope,
                 "matrix: budget relative to the mean column energy; column: to each column's own")
      ->capture_default_str();
  cmd.add_option("--column-terms", p.column_terms,
                 "keep exactly K coefficients per column instead of --target-error");
  cmd.add_option("--bits", f.bits,
                 "quantization bits 2..16 (each column's max to the largest code), or auto (the "
                 "error budget's quantization half)")
      ->capture_default_str();
  cmd.add_option("--level-scaling", f.level_scaling,
                 "uniform: one step per column (auto: one matrix-wide step); paper: values of "
                 "level l times 2^l first (4D paper §4.3)")
      ->capture_default_str();
  cmd.add_option("--transport", f.transport,
                 "what a row holds: diffuse (T = V cos/π) or visibility (V alone, for glossy "
                 "relighting by the triple product; needs --row-filter haar)")
      ->capture_default_str();
  cmd.add_option("--seed", p.seed, "job seed (jitter and dither)")->capture_default_str();
  cmd.add_option("--refine", f.refine,
                 "on: trace only where visibility changes (coarse probes, refined along "
                 "silhouettes; fully visible texels get their exact integral; cube light domain "
                 "only); off: brute force, K rays in every texel")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd.add_flag("--keep-staging", p.keep_staging,
               "leave the staging arrays (row-transformed T, transposed) in the store");
  cmd.add_option("--tile-size", p.tile_size,
                 "spatial tile edge of one BAKE_TILE task (power of two)")
      ->capture_default_str();
  cmd.add_option("--column-group", p.column_group, "columns per TRANSFORM_COLUMNS task")
      ->capture_default_str();
}

absl::StatusOr<BakeParams> ToParams(const BakeFlags& f) {
  BakeParams p = f.params;
  if (f.allow_uv_overlap) {
    absl::StatusOr<std::string> layout = WithUvOverlapAllowed(p.layout);
    if (!layout.ok()) return layout.status();
    p.layout = *layout;
  }
  for (absl::Status s : {Set(ParseWaveletFilter(f.row_filter), p.row_filter, "row_"),
                         Set(ParseColumnMode(f.column_mode), p.column_mode),
                         Set(ParseWaveletFilter(f.column_filter), p.column_filter, "column_"),
                         Set(ParseErrorScope(f.error_scope), p.error_scope),
                         Set(ParseLevelScaling(f.level_scaling), p.level_scaling),
                         Set(ParseTransport(f.transport), p.transport),
                         Set(ParseLightDomain(f.light_domain), p.light_domain)})
    if (!s.ok()) return s;
  p.refine = f.refine == "on";
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
