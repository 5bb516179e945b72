#pragma once
// Near-field relighting by planar area lights (Sun & Ramamoorthi 2009 §5)
// from a store baked over one expanded face (--light-domain plane:S). Per
// frame, per light: draw it into its source image and keep the largest
// source coefficients (runtime/near_field/light_canvas.h). Per sample x below the
// light plane, at distance z:
//
//   1. the face sees the light through q = s v + o (Eq. 29, s = zS/extent);
//   2. target-level truncation: the constant-light heuristic picks which
//      face coefficients to compute (core/products/target_selection.h, §5.3.3);
//   3. those coefficients L_k(x) by affine coupling, in two separable steps
//      (core/products/affine_propagation.h, Eq. 30, §5.3.1);
//   4. B(x) += Σ_k L_k(x) T_k(x) over the chosen k, T from the 4D-compressed
//      columns decoded once into per-cell rows (runtime/relight/cell_rows.h).
//
// Samples on or behind the light plane (z ≤ 0) receive nothing from it;
// lights add. B × the per-sample albedo is the outgoing radiance.
#include <filesystem>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/directions/light_domain.h"
#include "core/layouts/samples.h"
#include "core/products/coupling_table.h"
#include "runtime/near_field/area_light.h"
#include "runtime/near_field/light_canvas.h"
#include "runtime/relight/cell_rows.h"
#include "storage/store/store_reader.h"

namespace wavebake {

struct NearFieldOptions {
  double source_fraction = 0.01;         // of the R² source coefficients, per light
  double target_fraction = 0.30;         // of the N² face coefficients, per sample and light
  const CouplingTable* table = nullptr;  // memory-based couplings; null: computed (Eq. 16)
  int threads = 0;                       // 0: all cores
};

struct NearFieldStats {
  int lights = 0;
  int64_t sources = 0;      // kept, all lights
  int64_t lit_samples = 0;  // (sample, light) pairs in front of the light with a nonempty image
  int64_t targets = 0;      // propagated coefficients, all pairs
  double seconds = 0;       // the frame: canvases, selection, propagation, products
};

// Where a point stands relative to one light: the affine map of its face
// and the image [ax, bx] × [ay, by] of the light's canvas on the face
// (clipped to [0,1]²); lit = false on or behind the light plane (z ≤ 0) or
// when the image misses the face.
struct FaceView {
  bool lit = false;
  AffineMap2d map;
  double ax = 0, bx = 0, ay = 0, by = 0;
};
FaceView ViewFrom(const PlaneFace& face, const LightCanvas& canvas, Vec3 position);

// rgb [W*H*3] × the per-cell albedo (runtime/relight/relighter.h CellAlbedo): NaN where masked.
void MultiplyAlbedo(const SampleSet& samples, std::span<float> rgb);

// A plane-domain store opened for near-field relighting.
struct NearFieldStore {
  StoreInfo info;
  SampleSet samples;
  PlaneFace face{8, 4, kPosY};
  CellRows rows;
};

// Errors: not a store, a cube store (FailedPrecondition: relight it with
// --env), inconsistent arrays (named by the reader or CellRows::Decode).
absl::StatusOr<NearFieldStore> OpenNearFieldStore(const std::filesystem::path& store);

// The frame: rgb_out [W*H*3] = Σ_lights B × albedo, masked cells NaN.
// Errors: fractions outside (0, 1]; a table made for another R or N.
absl::StatusOr<NearFieldStats> RelightNearField(const NearFieldStore& store,
                                                std::span<const AreaLight> lights,
                                                const NearFieldOptions& options,
                                                std::span<float> rgb_out);

// The same lights treated as distant (Fig. 8c of the paper): every sample
// lit by the light's image on the face at `centre` (all coefficients, no
// truncation), ignoring where the sample is. rgb_out as above.
void RelightDistant(const NearFieldStore& store, std::span<const AreaLight> lights, Vec3 centre,
                    std::span<float> rgb_out);

// The mean position of the samples, the receivers' centre: where the
// distant treatment looks from (the paper's footnote 4, "the centre of the
// scene"; the bounding box's centre would sit high above a floor whenever a
// wall stands at its edge).
Vec3 SampleCentre(const SampleSet& samples);

// The face coefficients (row basis, rgb[3k + c] for Mallat index k) of
// `canvas` seen from `position`, every source and target kept; zeros when
// the point is not in front of the light. For RelightDistant and tests.
std::vector<float> FaceCoefficients(const PlaneFace& face, const LightCanvas& canvas,
                                    Vec3 position);

}  // namespace wavebake
