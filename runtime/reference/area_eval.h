#pragma once
// `wavebake eval STORE --reference --area-light LIGHT.json [--json]`: how far
// near-field relighting of a plane-domain store (runtime/near_field/near_field.h) is
// from the independent Monte-Carlo reference over the lights' areas
// (runtime/reference/area_reference.h), next to the same lights treated as distant
// (their image on the face at the scene centre lighting every sample, the
// paper's Fig. 8c), and what the store's expanded face misses at grazing
// angles (§5.4.3).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "runtime/near_field/near_field.h"
#include "runtime/reference/area_reference.h"
#include "runtime/reference/eval.h"

namespace wavebake {

struct AreaEvalOptions {
  NearFieldOptions near;
  AreaReferenceOptions reference;  // axis and epsilon are the store's
  bool distant = true;
};

// The reference restricted to receivers facing the light plane (n·axis ≥
// 0.9, within 26° of it): where the expanded face sees all of a light above
// them (§5.2.1). Other cells are NaN, so CompareToReference skips them.
std::vector<float> FacingOnly(const SampleSet& samples, const FaceFrame& frame,
                              std::span<const float> reference);

struct AreaEvalReport {
  ErrorStats near_field, distant;          // seconds: one frame (near field), the frame (distant)
  ErrorStats near_facing, distant_facing;  // over the receivers facing the plane only
  bool has_distant = false;
  NearFieldStats near_stats;
  double face_size = 0;  // S of the store
  double reference_rel_se = 0, reference_seconds = 0;
  int64_t reference_rays = 0;
  std::vector<double> face_sizes, grazing_loss;  // the reference's §5.4.3 split
  double store_grazing_loss = 0;                 // interpolated at S
  std::vector<float> reference_rgb;              // the reference image, [W*H*3]
};

absl::StatusOr<AreaEvalReport> EvaluateAreaLights(const NearFieldStore& store,
                                                  std::span<const AreaLight> lights,
                                                  const AreaEvalOptions& options);

// {"near_field": {rel_rms, max_abs, psnr, seconds}, "distant": {...} | null,
//  "near_field_facing", "distant_facing": the same over FacingOnly,
//  "source_fraction", "target_fraction", "targets_per_sample", "face_size",
//  "reference": {"rel_se", "rays", "seconds"},
//  "grazing_loss": [{"face_size", "loss"}...], "store_grazing_loss"}
nlohmann::json AreaEvalJson(const AreaEvalReport& report, const AreaEvalOptions& options);

}  // namespace wavebake
