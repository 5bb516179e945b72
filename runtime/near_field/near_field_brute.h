#pragma once
// The brute-force baseline of near-field relighting: per sample and light,
// resample the light onto the sample's face in the pixel domain — each
// texel the exact mean of the light's source image over the texel's
// footprint in the light plane (box weights) — then the dense
// dot product with the sample's row of T in the pixel basis (the rows of
// runtime/relight/cell_rows.h through the inverse row transform, once at creation).
// No truncation anywhere: it is what the wavelet path computes with every
// source and target coefficient kept, by another road (bench/near_field.cc
// times the two; tests/driver/near_field_test.cc compares them).
#include <span>
#include <vector>

#include "runtime/near_field/near_field.h"

namespace wavebake {

// How a face image is resampled from the light's canvas: every texel on its
// own (the brute force), or separably along the axes (the same weights; a
// faster baseline that relies on the axis-aligned footprints, as the
// wavelet path's two steps do).
enum class BruteResample { kPerTexel, kSeparable };

class BruteForceNearField {
 public:
  explicit BruteForceNearField(const NearFieldStore& store);

  // rgb_out [W*H*3] = Σ_lights B × albedo, masked cells NaN.
  void Relight(std::span<const LightCanvas> lights, int threads, std::span<float> rgb_out,
               BruteResample mode = BruteResample::kPerTexel) const;

  // The face image of `canvas` seen from `position`: [N²·3] texel means,
  // rgb[3(y·N + x) + c]; zeros when the point is not in front of the light.
  std::vector<float> FaceImage(const LightCanvas& canvas, Vec3 position) const;

 private:
  const NearFieldStore& store_;
  std::vector<float> pixel_rows_;  // [cells × N²]: rows in the pixel basis, 0 where masked
};

}  // namespace wavebake
