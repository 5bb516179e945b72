#pragma once
// Entry points of `wavebake relight STORE --area-light LIGHT.json ...`
// (runtime/near_field/near_field.h): one frame to an image or mesh, or a light moving
// over frames (`--area-light-sequence SEQ.json`, runtime/near_field/area_light.h) into a
// directory of frames and their timings.
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "runtime/near_field/near_field.h"

namespace wavebake::driver {

struct AreaRelightOptions {
  NearFieldOptions near;
  float exposure_stops = 0;
  bool distant = false;  // treat the lights as distant instead (a comparison)
};

// Every light of every file (they add). Errors name the file and field.
absl::StatusOr<std::vector<AreaLight>> LoadAllAreaLights(
    std::span<const std::filesystem::path> files);

// One frame written by out's extension (.png, .exr: camera layouts; .ply:
// mesh layouts), as `relight --env` does. Returns the frame's statistics.
absl::StatusOr<NearFieldStats> RelightAreaToFile(const std::filesystem::path& store,
                                                 std::span<const std::filesystem::path> lights,
                                                 const AreaRelightOptions& options,
                                                 const std::filesystem::path& out);

struct AreaSequenceSummary {
  int frames = 0;
  double mean_seconds = 0, median_seconds = 0;  // per frame, relighting only
};

// The sequence's light (plus any fixed `lights`), frame f written to
// out_dir/frame_NNNN.EXT and its time to out_dir/timing.csv
// (frame,seconds,lit_samples,targets).
absl::StatusOr<AreaSequenceSummary> RelightAreaSequence(
    const std::filesystem::path& store, const std::filesystem::path& sequence,
    std::span<const std::filesystem::path> lights, const AreaRelightOptions& options,
    const std::filesystem::path& out_dir, const std::string& frame_extension);

}  // namespace wavebake::driver
