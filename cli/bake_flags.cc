#include "cli/bake_flags.h"

namespace wavebake::cli {

void AddBakeFlags(CLI::App& cmd, BakeFlags& flags) {
  BakeParams& p = flags.params;
  BakeParamWords& f = flags.words;
  cmd.add_option("--light-res", p.light_res,
                 "cubemap texels per face edge N (power of two, 8..256)")
      ->capture_default_str();
  cmd.add_option("--light-domain", f.light_domain,
                 "cube | plane:S[:AXIS]: one face of size S (3..10) aligned with a light plane "
                 "normal to AXIS (default +Y), for --area-light")
      ->capture_default_str();
  cmd.add_option("--layout", p.layout,
                 "spatial layout: camera[:WxH] | grid | hilbert:WxH | uv[:WxH] | uv1[:WxH] "
                 "(lightmap texels of UV channel 0 or 1, default 256x256); uv options after "
                 "commas: ,fill=zero|push-pull|dilate (texels no chart covers), "
                 ",allow-overlap (as --allow-uv-overlap)")
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
  cmd.add_option("--bounces", f.bounces,
                 "diffuse interreflection: light bounced B times off the scene's surfaces, 0..8, "
                 "or auto (until the next bounce adds less than half of --target-error); 0: "
                 "direct light only. Vertex layouts (hilbert, grid), diffuse transport")
      ->capture_default_str();
  cmd.add_option("--gather-rays", p.gather_rays,
                 "stratified directions per sample that gather each bounce (rounded up to a "
                 "square)")
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
  cmd.add_option("--column-group", p.column_group,
                 "columns per TRANSFORM_COLUMNS task (0: up to 1024, as many as fit 256 MiB of "
                 "column images)")
      ->capture_default_str();
}

}  // namespace wavebake::cli
