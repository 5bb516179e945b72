#pragma once
// Every parameter of a bake job (DESIGN.md §5 flags). Plain data; validated
// by ValidateBakeParams (core/bake/bake_params_io.h), recorded in the store's .zattrs.
#include <cstdint>
#include <string>

#include "core/directions/light_domain.h"

namespace wavebake {

enum class ColumnMode { k2d, kFull, kAdaptive };
enum class WaveletFilter { kHaar, kDaub4, kLeGall53, kCdf97 };
enum class ErrorScope { kMatrix, kColumn };
// How kept coefficients are scaled before quantization (DESIGN.md §1
// "Scaling and quantization", core/columns/quantizer.h): kUniform quantizes every
// value with the column's step (rate-distortion optimal for an MSE budget on
// normalized filters); kPaper first multiplies level-l values by 2^l (4D
// paper §4.3), spending ~l extra bits on fine levels.
enum class LevelScaling { kUniform, kPaper };
// What a row of the matrix holds (DESIGN.md §1 "What a row holds"): kDiffuse
// the transport T = Ω V cos/π, kVisibility the visibility V alone, for the
// triple product with a BRDF in the global frame (runtime/glossy/glossy_relighter.h).
enum class Transport { kDiffuse, kVisibility };

inline constexpr int kMaxBounces = 8;
inline constexpr int kAutoBounces = -1;

struct BakeParams {
  int light_res = 32;             // N: texels per cube face edge, power of two in 8..256
  LightDomain light_domain;       // the cube (default) or one expanded plane face
  std::string layout = "camera";  // camera[:WxH] | grid | hilbert:WxH | uv[1][:WxH][,OPTIONS]
                                  // (ParseLayout, core/layouts/layout.h)
  int supersample = 4;            // K jittered directions per texel (rounded to a square)
  WaveletFilter row_filter = WaveletFilter::kHaar;  // haar | daub4
  ColumnMode column_mode = ColumnMode::kAdaptive;
  WaveletFilter column_filter = WaveletFilter::kHaar;  // haar | legall53 | cdf97
  double target_error = 0.01;  // absolute budget, DESIGN.md §1 "Coefficient selection"
  ErrorScope error_scope = ErrorScope::kMatrix;
  int column_terms = 0;  // > 0: keep a fixed K per column instead of the target
  int bits = 0;          // 0 = auto, else 2..16
  LevelScaling level_scaling = LevelScaling::kUniform;
  Transport transport = Transport::kDiffuse;
  uint64_t seed = 1;
  int tile_size = 32;    // spatial tile edge (cells) of BAKE_TILE
  int column_group = 0;  // columns per TRANSFORM_COLUMNS task; 0: the plan's (core/bake/job_plan.h)
  float ray_epsilon = 0;  // 0 = 1e-4 × scene bounding-box diagonal
  // Diffuse interreflection (core/transport/bounce_gather.h): T = T_0 + … + T_B,
  // each bounce gathered from the previous one over `gather_rays` stratified
  // directions per sample. 0 (the default) is direct light only: every
  // store baked before bounces existed. 0..kMaxBounces, or kAutoBounces:
  // as many as the scene needs (core/transport/bounce_gather.h AutoBounces),
  // resolved by every worker alike from the gather operator.
  int bounces = 0;
  // 256: at 64 the gather's noise (1/√R of the bounced light per sample) was
  // the largest error of a bounce store (the bunny under builtin:sky, N = 32,
  // B = 2: 1.6 % at 64 rays, 0.98 % at 256, against 0.81 % of direct light
  // alone; docs/RESULTS.md chart 12).
  int gather_rays = 256;
  // Visibility refinement (core/transport/refined_row.h): trace only where visibility
  // changes. false = brute force, every texel's K rays (core/transport/transport_row.h).
  // Refinement works on the cube's faces (core/transport/refine_plan.h) and on the
  // cosine-weighted T; a plane light domain and a visibility transport are
  // always traced by brute force (see refines()).
  bool refine = true;
  // Not a property of the matrix (not recorded with it): FINALIZE leaves
  // staging/ in the store for inspection.
  bool keep_staging = false;
  // An update bake (worker/tiles/row_reuse.h), not recorded with the matrix
  // either: the old store (baked with keep_staging, the same parameters)
  // whose staged rows are reused where the scene edit cannot reach them; ""
  // is a full bake. update_exact: the whole column stage runs from the
  // merged rows (the store is byte-identical to a full bake's). A client
  // of a coordinator names the old store by its job instead (update_job: an
  // id or an output_name), and the coordinator sets update_from.
  std::string update_from;
  bool update_exact = false;
  std::string update_job;
  bool updates() const { return !update_from.empty() || !update_job.empty(); }

  // Whether the rows are traced by refinement: asked for, on the cube, for T.
  bool refines() const {
    return refine && !light_domain.is_plane() && transport == Transport::kDiffuse;
  }
};

}  // namespace wavebake
