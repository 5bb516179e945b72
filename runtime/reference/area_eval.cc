#include "runtime/reference/area_eval.h"

#include <chrono>
#include <cmath>

namespace wavebake {

std::vector<float> FacingOnly(const SampleSet& samples, const FaceFrame& frame,
                              std::span<const float> reference) {
  std::vector<float> out(reference.begin(), reference.end());
  for (int cell = 0; cell < samples.cells(); ++cell) {
    const int32_t id = samples.grid[cell];
    if (id >= 0 && Dot(samples.normal[id], frame.major) >= 0.9f) continue;
    for (int c = 0; c < 3; ++c) out[3 * size_t(cell) + c] = std::nanf("");
  }
  return out;
}

absl::StatusOr<AreaEvalReport> EvaluateAreaLights(const NearFieldStore& store,
                                                  std::span<const AreaLight> lights,
                                                  const AreaEvalOptions& options) {
  absl::StatusOr<RayCaster> caster = BuildBakedScene(store.info);
  if (!caster.ok()) return caster.status();
  AreaReferenceOptions ref_options = options.reference;
  ref_options.axis = store.face.axis();
  ref_options.epsilon = BakedEpsilon(store.info, *caster);
  absl::StatusOr<AreaReferenceResult> ref =
      ComputeAreaReference(*caster, store.samples, lights, ref_options);
  if (!ref.ok()) return ref.status();

  AreaEvalReport report;
  report.face_size = store.face.size();
  report.reference_rel_se = ref->rel_se;
  report.reference_rays = ref->rays;
  report.reference_seconds = ref->seconds;
  report.face_sizes = ref_options.face_sizes;
  report.grazing_loss = ref->grazing_loss;
  report.reference_rgb = ref->rgb;
  // The loss at the store's own S, linear between the measured sizes.
  for (size_t j = 0; j + 1 < report.face_sizes.size(); ++j) {
    const double a = report.face_sizes[j], b = report.face_sizes[j + 1];
    if (report.face_size >= a && report.face_size <= b)
      report.store_grazing_loss =
          report.grazing_loss[j] +
          (report.face_size - a) / (b - a) * (report.grazing_loss[j + 1] - report.grazing_loss[j]);
  }

  std::vector<float> rgb(3 * size_t(store.samples.cells()));
  absl::StatusOr<NearFieldStats> stats = RelightNearField(store, lights, options.near, rgb);
  if (!stats.ok()) return stats.status();
  report.near_stats = *stats;
  const std::vector<float> facing = FacingOnly(store.samples, store.face.frame(), ref->rgb);
  report.near_field = CompareToReference(rgb, ref->rgb);
  report.near_field.seconds = stats->seconds;
  report.near_facing = CompareToReference(rgb, facing);
  if (options.distant) {
    const auto t0 = std::chrono::steady_clock::now();
    RelightDistant(store, lights, SampleCentre(store.samples), rgb);
    report.distant = CompareToReference(rgb, ref->rgb);
    report.distant_facing = CompareToReference(rgb, facing);
    report.distant.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report.has_distant = true;
  }
  return report;
}

namespace {
nlohmann::json Stats(const ErrorStats& e) {
  return {{"rel_rms", e.rel_rms},
          {"max_abs", e.max_abs},
          {"psnr", std::isfinite(e.psnr) ? nlohmann::json(e.psnr) : nlohmann::json(nullptr)},
          {"seconds", e.seconds}};
}
}  // namespace

nlohmann::json AreaEvalJson(const AreaEvalReport& r, const AreaEvalOptions& o) {
  nlohmann::json loss = nlohmann::json::array();
  for (size_t j = 0; j < r.face_sizes.size(); ++j)
    loss.push_back({{"face_size", r.face_sizes[j]}, {"loss", r.grazing_loss[j]}});
  const double pairs = std::max<int64_t>(1, r.near_stats.lit_samples);
  return {{"near_field", Stats(r.near_field)},
          {"distant", r.has_distant ? Stats(r.distant) : nlohmann::json(nullptr)},
          {"near_field_facing", Stats(r.near_facing)},
          {"distant_facing", r.has_distant ? Stats(r.distant_facing) : nlohmann::json(nullptr)},
          {"source_fraction", o.near.source_fraction},
          {"target_fraction", o.near.target_fraction},
          {"sources", r.near_stats.sources},
          {"targets_per_sample", r.near_stats.targets / pairs},
          {"face_size", r.face_size},
          {"reference",
           {{"rel_se", r.reference_rel_se},
            {"rays", r.reference_rays},
            {"seconds", r.reference_seconds}}},
          {"grazing_loss", loss},
          {"store_grazing_loss", r.store_grazing_loss}};
}

}  // namespace wavebake
