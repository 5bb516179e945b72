// The sequence modes of `wavebake relight`: a rotating environment
// (runtime/relight_sequence.h) and material editing (runtime/
// material_sequence.h), each writing its frames and errors.csv to --out.
#include <algorithm>
#include <cstdio>
#include <vector>

#include "cli/command_error.h"
#include "cli/relight_flags.h"
#include "runtime/material_sequence.h"
#include "runtime/relight_sequence.h"

namespace wavebake::cli {
namespace {

template <typename Frames>
void PrintSummary(const Frames& frames, const std::string& out, const char* versus) {
  double sum = 0, worst = 0, seconds = 0;
  for (const auto& fr : frames) {
    sum += fr.rel_rms;
    worst = std::max(worst, fr.rel_rms);
    seconds += fr.seconds;
  }
  const double n = static_cast<double>(frames.size());
  std::printf(
      "wrote %zu frames and errors.csv to %s: rel_rms vs %s mean %.5f max %.5f last %.5f, "
      "%.2f ms/frame\n",
      frames.size(), out.c_str(), versus, sum / n, worst, frames.back().rel_rms, 1e3 * seconds / n);
}

}  // namespace

void RunRotateSequence(const RelightFlags& f) {
  absl::StatusOr<RotateSequence> rotation = ParseRotateSequence(f.rotate_sequence);
  if (!rotation.ok()) Fail("relight", rotation.status());
  const std::string inc = f.incremental.empty() ? "per-band" : f.incremental;
  const SequenceMode mode = inc == "none"    ? SequenceMode::kNonIncremental
                            : inc == "basic" ? SequenceMode::kBasic
                                             : SequenceMode::kPerBand;
  SequenceOptions options{.rotation = *rotation,
                          .terms = f.terms,
                          .mode = mode,
                          .exposure_stops = f.exposure,
                          .out_dir = f.out,
                          .frame_extension = "." + f.frame_format};
  absl::StatusOr<std::vector<SequenceFrame>> frames = RelightSequence(f.store, f.env, options);
  if (!frames.ok()) Fail("relight", frames.status());
  PrintSummary(*frames, f.out, "all lights");
}

void RunBrdfSequence(const RelightFlags& f) {
  if (!f.rotate_sequence.empty())
    Fail("relight", "brdf-sequence: give --rotate-sequence or --brdf-sequence, not both",
         kExitBadInput);
  absl::StatusOr<BrdfSequence> sequence = ParseBrdfSequence(f.brdf_sequence);
  if (!sequence.ok()) Fail("relight", sequence.status());
  const std::string inc = f.incremental.empty() ? "basic" : f.incremental;
  if (inc != "basic" && inc != "none")
    Fail("relight",
         "incremental: '" + inc +
             "' with --brdf-sequence must be basic (Overbeck ch. 4) or none; per-band bands "
             "the lighting, not a BRDF",
         kExitBadInput);
  MaterialSequenceOptions options{
      .sequence = *sequence,
      .terms = f.terms,
      .mode = inc == "basic" ? MaterialMode::kBasic : MaterialMode::kNonIncremental,
      .glossy = GlossyOf(f.glossy, "relight"),
      .exposure_stops = f.exposure,
      .out_dir = f.out,
      .frame_extension = "." + f.frame_format};
  absl::StatusOr<std::vector<MaterialFrame>> frames =
      RelightMaterialSequence(f.store, f.env, options);
  if (!frames.ok()) Fail("relight", frames.status());
  PrintSummary(*frames, f.out, "every BRDF term");
}

}  // namespace wavebake::cli
