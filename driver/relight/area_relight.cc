#include "driver/relight/area_relight.h"

#include <algorithm>
#include <cstdio>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "driver/relight/relight_sequence.h"
#include "runtime/relight/store_relight.h"
#include "storage/files/atomic_file.h"

namespace wavebake::driver {
namespace {

absl::StatusOr<std::vector<float>> Frame(const NearFieldStore& store,
                                         std::span<const AreaLight> lights,
                                         const AreaRelightOptions& o, NearFieldStats* stats) {
  std::vector<float> rgb(3 * size_t(store.samples.cells()));
  if (o.distant) {
    RelightDistant(store, lights, SampleCentre(store.samples), rgb);
    return rgb;
  }
  absl::StatusOr<NearFieldStats> s = RelightNearField(store, lights, o.near, rgb);
  if (!s.ok()) return s.status();
  if (stats) *stats = *s;
  return rgb;
}

}  // namespace

absl::StatusOr<std::vector<AreaLight>> LoadAllAreaLights(
    std::span<const std::filesystem::path> files) {
  std::vector<AreaLight> all;
  for (const std::filesystem::path& f : files) {
    absl::StatusOr<std::vector<AreaLight>> l = LoadAreaLights(f);
    if (!l.ok()) return l.status();
    all.insert(all.end(), l->begin(), l->end());
  }
  return all;
}

absl::StatusOr<NearFieldStats> RelightAreaToFile(const std::filesystem::path& store_path,
                                                 std::span<const std::filesystem::path> files,
                                                 const AreaRelightOptions& o,
                                                 const std::filesystem::path& out) {
  if (files.empty()) return absl::InvalidArgumentError("area_light: give at least one LIGHT.json");
  if (absl::Status s = CheckRelitPath(out); !s.ok()) return s;
  absl::StatusOr<std::vector<AreaLight>> lights = LoadAllAreaLights(files);
  if (!lights.ok()) return lights.status();
  absl::StatusOr<NearFieldStore> store = OpenNearFieldStore(store_path);
  if (!store.ok()) return store.status();
  NearFieldStats stats;
  absl::StatusOr<std::vector<float>> rgb = Frame(*store, *lights, o, &stats);
  if (!rgb.ok()) return rgb.status();
  if (absl::Status s = WriteRelit(store->info, store->samples, *rgb, o.exposure_stops, out);
      !s.ok())
    return s;
  return stats;
}

absl::StatusOr<AreaSequenceSummary> RelightAreaSequence(
    const std::filesystem::path& store_path, const std::filesystem::path& sequence,
    std::span<const std::filesystem::path> files, const AreaRelightOptions& o,
    const std::filesystem::path& out_dir, const std::string& ext) {
  absl::StatusOr<AreaLightSequence> seq = LoadAreaLightSequence(sequence);
  if (!seq.ok()) return seq.status();
  absl::StatusOr<std::vector<AreaLight>> fixed = LoadAllAreaLights(files);
  if (!fixed.ok()) return fixed.status();
  if (absl::Status s = CheckRelitPath(out_dir / ("frame" + ext)); !s.ok()) return s;
  absl::StatusOr<NearFieldStore> store = OpenNearFieldStore(store_path);
  if (!store.ok()) return store.status();
  if (absl::Status s = CreateDirectories(out_dir); !s.ok()) return s;
  std::string csv = "frame,seconds,lit_samples,targets\n";
  std::vector<double> seconds;
  for (int f = 0; f < seq->frames; ++f) {
    std::vector<AreaLight> lights = *fixed;
    lights.push_back(seq->Frame(f));
    NearFieldStats stats;
    absl::StatusOr<std::vector<float>> rgb = Frame(*store, lights, o, &stats);
    if (!rgb.ok()) return rgb.status();
    seconds.push_back(stats.seconds);
    absl::StrAppendFormat(&csv, "%d,%.6f,%d,%d\n", f, stats.seconds, stats.lit_samples,
                          stats.targets);
    const std::filesystem::path frame = SequenceFramePath(out_dir, f, ext);
    if (absl::Status s = WriteRelit(store->info, store->samples, *rgb, o.exposure_stops, frame);
        !s.ok())
      return s;
  }
  if (absl::Status s = AtomicWriteText(out_dir / "timing.csv", csv); !s.ok()) return s;
  AreaSequenceSummary sum;
  sum.frames = seq->frames;
  for (double s : seconds) sum.mean_seconds += s / seconds.size();
  std::vector<double> sorted = seconds;
  std::sort(sorted.begin(), sorted.end());
  sum.median_seconds = sorted[sorted.size() / 2];
  return sum;
}

}  // namespace wavebake::driver
