#include "driver/relight/area_light_commands.h"

#include <filesystem>
#include <optional>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/products/coupling_table.h"
#include "driver/relight/area_relight.h"
#include "runtime/reference/area_eval.h"
#include "runtime/relight/finite_output.h"
#include "runtime/relight/store_relight.h"

namespace wavebake::driver {
namespace {

std::vector<std::filesystem::path> Paths(const std::vector<std::string>& files) {
  return {files.begin(), files.end()};
}

// The memory-based table for the lights' R and the store's N, over the
// scales a scene of this size can produce (bench/near_field.cc measures it).
absl::StatusOr<std::optional<CouplingTable>> MaybeTable(const AreaLightCommand& c,
                                                        const std::vector<AreaLight>& lights,
                                                        int n) {
  if (!c.table || lights.empty()) return std::optional<CouplingTable>();
  absl::StatusOr<CouplingTable> t = CouplingTable::Build(
      {.source_res = lights.front().resolution, .target_res = n, .s_min = 0.05, .s_max = 40});
  if (!t.ok()) return t.status();
  return std::optional<CouplingTable>(*std::move(t));
}

}  // namespace

absl::StatusOr<std::string> RelightWithAreaLights(const AreaLightCommand& c) {
  if (absl::Status s = CheckExposure(c.exposure); !s.ok()) return s;
  AreaRelightOptions o;
  o.near = {.source_fraction = c.source_fraction,
            .target_fraction = c.target_fraction,
            .threads = c.threads};
  o.exposure_stops = c.exposure;
  o.distant = c.distant;
  const std::vector<std::filesystem::path> files = Paths(c.lights);
  if (!c.sequence.empty()) {
    absl::StatusOr<AreaSequenceSummary> s =
        RelightAreaSequence(c.store, c.sequence, files, o, c.out, c.frame_extension);
    if (!s.ok()) return s.status();
    return absl::StrFormat("wrote %d frames and timing.csv to %s: %.2f ms/frame median (%.1f fps)",
                           s->frames, c.out, 1e3 * s->median_seconds,
                           s->median_seconds > 0 ? 1 / s->median_seconds : 0.0);
  }
  absl::StatusOr<NearFieldStats> s = RelightAreaToFile(c.store, files, o, c.out);
  if (!s.ok()) return s.status();
  if (c.distant) return absl::StrCat("wrote ", c.out, " (lights treated as distant)");
  return absl::StrFormat(
      "wrote %s: %d light(s), %d source terms, %.1f targets per lit sample, "
      "%.2f ms",
      c.out, s->lights, s->sources, s->lit_samples ? double(s->targets) / s->lit_samples : 0.0,
      1e3 * s->seconds);
}

absl::StatusOr<std::string> EvaluateWithAreaLights(const AreaLightCommand& c, int reference_batches,
                                                   bool json) {
  if (absl::Status s = CheckExposure(c.exposure); !s.ok()) return s;
  const std::vector<std::filesystem::path> files = Paths(c.lights);
  absl::StatusOr<std::vector<AreaLight>> lights = LoadAllAreaLights(files);
  if (!lights.ok()) return lights.status();
  if (lights->empty()) return absl::InvalidArgumentError("area_light: no light given");
  absl::StatusOr<NearFieldStore> store = OpenNearFieldStore(c.store);
  if (!store.ok()) return store.status();
  absl::StatusOr<std::optional<CouplingTable>> table = MaybeTable(c, *lights, store->face.n());
  if (!table.ok()) return table.status();
  AreaEvalOptions o;
  o.near = {.source_fraction = c.source_fraction,
            .target_fraction = c.target_fraction,
            .table = table->has_value() ? &**table : nullptr,
            .threads = c.threads};
  o.reference.batches = reference_batches;
  o.reference.threads = c.threads;
  if (!c.reference_out.empty())
    if (absl::Status s = CheckRelitPath(c.reference_out); !s.ok()) return s;
  absl::StatusOr<AreaEvalReport> r = EvaluateAreaLights(*store, *lights, o);
  if (!r.ok()) return r.status();
  if (!c.reference_out.empty())
    if (absl::Status s =
            WriteRelit(store->info, store->samples, r->reference_rgb, c.exposure, c.reference_out);
        !s.ok())
      return s;
  if (json) return AreaEvalJson(*r, o).dump();
  std::string text = absl::StrFormat(
      "reference   rel_se %.5f  %d rays  %.1f s\n"
      "near field  rel_rms %.5f  max_abs %.5g  psnr %6.2f dB  %.3f s  (%.0f%% source, %.0f%% "
      "target terms)\n",
      r->reference_rel_se, r->reference_rays, r->reference_seconds, r->near_field.rel_rms,
      r->near_field.max_abs, r->near_field.psnr, r->near_field.seconds, 100 * c.source_fraction,
      100 * c.target_fraction);
  if (r->has_distant)
    absl::StrAppendFormat(&text, "distant     rel_rms %.5f  max_abs %.5g  psnr %6.2f dB\n",
                          r->distant.rel_rms, r->distant.max_abs, r->distant.psnr);
  absl::StrAppendFormat(&text,
                        "facing the light plane only (n·axis ≥ 0.9): near field rel_rms %.5f, "
                        "distant %.5f\n",
                        r->near_facing.rel_rms, r->distant_facing.rel_rms);
  absl::StrAppendFormat(&text, "grazing loss of the plane:%g face: %.2f%% of the energy",
                        r->face_size, 100 * r->store_grazing_loss);
  return text;
}

}  // namespace wavebake::driver
