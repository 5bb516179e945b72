#pragma once
// Environments generated in code (DESIGN.md §5 `builtin:constant`,
// `builtin:sky`), so the project needs no data files at run time.
#include "core/util/vec3.h"
#include "runtime/env/env_map.h"

namespace wavebake {

// L ≡ 1 everywhere (the white-furnace environment), as a small lat-long map.
EnvMap MakeConstantEnv();

// builtin:sky. Angles in degrees; azimuths are the lat-long φ (latlong.h:
// 0 = −Z, +90 = +X, −90 = −X, ±180 = +Z), elevations are above the horizon.
// The sun and the area light add to the sky beneath them, so
//   ∫ L dω = π (zenith + horizon) + 2π ground
//          + 2π (1 − cos sun_radius) · sun
//          + Δazimuth · (sin elev_max − sin elev_min) · area_light.
struct SkyParams {
  int width = 512;                    // height = width / 2
  Vec3 zenith{0.20f, 0.35f, 0.90f};   // sky radiance straight up
  Vec3 horizon{0.80f, 0.85f, 0.95f};  // linear in sin(elevation) up to zenith
  Vec3 ground{0.10f, 0.09f, 0.08f};   // uniform below the horizon
  double sun_elevation = 35, sun_azimuth = 60, sun_radius = 1.5;
  Vec3 sun{2000.0f, 1800.0f, 1500.0f};  // radiance of the disk: tiny and very bright
  // A rectangle in (azimuth, elevation), e.g. a bright window or softbox;
  // azimuths within [−180, 180], no wrap.
  double area_azimuth_min = -150, area_azimuth_max = -110;
  double area_elevation_min = 10, area_elevation_max = 30;
  Vec3 area_light{6.0f, 6.0f, 6.0f};
};

// Each pixel is the mean over its footprint: exact for the gradient and the
// rectangle, 16 × 16 cells for the disk's edge; the integral above holds to
// ~1e-4.
EnvMap MakeSkyEnv(const SkyParams& params = {});

}  // namespace wavebake
