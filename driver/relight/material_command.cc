#include "driver/relight/material_command.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "driver/relight/material_sequence.h"

namespace wavebake::driver {

absl::StatusOr<std::string> RelightMaterialSequence(const MaterialCommand& c) {
  absl::StatusOr<BrdfSequence> sequence = ParseBrdfSequence(c.sequence);
  if (!sequence.ok()) return sequence.status();
  const std::string inc = c.incremental.empty() ? "basic" : c.incremental;
  if (inc != "basic" && inc != "none")
    return absl::InvalidArgumentError(absl::StrCat(
        "incremental: '", inc,
        "' with --brdf-sequence must be basic (Overbeck ch. 4) or none; per-band bands the "
        "lighting, not a BRDF"));
  MaterialSequenceOptions options{
      .sequence = *sequence,
      .terms = c.terms,
      .mode = inc == "basic" ? MaterialMode::kBasic : MaterialMode::kNonIncremental,
      .glossy = c.glossy,
      .exposure_stops = c.exposure,
      .out_dir = c.out,
      .frame_extension = c.frame_extension};
  absl::StatusOr<std::vector<MaterialFrame>> frames =
      RelightMaterialSequence(c.store, c.env, options);
  if (!frames.ok()) return frames.status();
  double sum = 0, worst = 0, seconds = 0;
  for (const MaterialFrame& f : *frames) {
    sum += f.rel_rms;
    worst = std::max(worst, f.rel_rms);
    seconds += f.seconds;
  }
  const double n = static_cast<double>(frames->size());
  return absl::StrFormat(
      "wrote %zu frames and errors.csv to %s: rel_rms vs every BRDF term mean %.5f max %.5f "
      "last %.5f, %.2f ms/frame",
      frames->size(), c.out, sum / n, worst, frames->back().rel_rms, 1e3 * seconds / n);
}

}  // namespace wavebake::driver
