#include "driver/relight/relight_command.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "driver/relight/material_command.h"
#include "driver/relight/relight_sequence.h"
#include "driver/relight/relight_to_file.h"
#include "runtime/relight/finite_output.h"

namespace wavebake::driver {
namespace {

absl::StatusOr<std::string> RelightRotating(const RelightCommand& c) {
  absl::StatusOr<RotateSequence> rotation = ParseRotateSequence(c.rotate_sequence);
  if (!rotation.ok()) return rotation.status();
  const SequenceMode mode = c.incremental == "none"    ? SequenceMode::kNonIncremental
                            : c.incremental == "basic" ? SequenceMode::kBasic
                                                       : SequenceMode::kPerBand;
  SequenceOptions options{.rotation = *rotation,
                          .terms = c.terms,
                          .mode = mode,
                          .exposure_stops = c.exposure,
                          .out_dir = c.out,
                          .frame_extension = c.frame_extension};
  absl::StatusOr<std::vector<SequenceFrame>> frames = RelightSequence(c.store, c.env, options);
  if (!frames.ok()) return frames.status();
  const SequenceSummary sum = Summarize(*frames);
  return absl::StrFormat(
      "wrote %zu frames and errors.csv to %s: rel_rms vs all lights mean %.5f max %.5f, "
      "%.2f ms/frame",
      frames->size(), c.out, sum.mean_rel_rms, sum.max_rel_rms, 1e3 * sum.mean_seconds);
}

}  // namespace

absl::StatusOr<std::string> Relight(const RelightCommand& c) {
  // Before any work: a sequence would otherwise fail at its first frame.
  if (absl::Status s = CheckExposure(c.exposure); !s.ok()) return s;
  if (!c.brdf_sequence.empty() && !c.rotate_sequence.empty())
    return absl::InvalidArgumentError(
        "brdf-sequence: give --rotate-sequence or --brdf-sequence, not both");
  if (!c.brdf_sequence.empty())
    return RelightMaterialSequence({c.store, c.env, c.out, c.brdf_sequence, c.incremental, c.terms,
                                    c.glossy, c.exposure, c.frame_extension});
  if (!c.rotate_sequence.empty()) return RelightRotating(c);
  if (absl::Status s =
          RelightStoreToFile(c.store, c.env, c.terms, c.rotate, c.exposure, c.out, c.glossy);
      !s.ok())
    return s;
  return absl::StrCat("wrote ", c.out);
}

}  // namespace wavebake::driver
