#pragma once
// `wavebake relight --rotate-sequence START:END:FRAMES`: the environment
// turned about +Y from START to END degrees over FRAMES frames, each frame
// relit with `terms` wavelet lights, either from scratch (non-incremental,
// Ng et al. 2003), basic-incrementally (Overbeck ch. 4, never reset: the
// ghosting baseline) or per-band incrementally (Overbeck ch. 6, §6.2.2;
// runtime/relight/incremental.h). Each frame's error is measured against the same
// frame relit with every wavelet light (the store's best answer), so the
// number isolates what the lighting approximation costs.
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "storage/files/atomic_file.h"

namespace wavebake::driver {

enum class SequenceMode { kNonIncremental, kBasic, kPerBand };

struct RotateSequence {
  double start_degrees = 0, end_degrees = 360;
  int frames = 0;  // ≥ 1; frame i is at start + (end − start)·i / max(frames − 1, 1)
};

// "START:END:FRAMES"; errors name the `rotate-sequence` flag.
absl::StatusOr<RotateSequence> ParseRotateSequence(std::string_view spec);

struct SequenceFrame {
  int index = 0;
  double degrees = 0;
  double rel_rms = 0;  // vs all-lights relighting of this frame, unmasked cells, RGB
  double seconds = 0;  // lighting + relighting of this frame (not the all-lights reference)
};

struct SequenceOptions {
  RotateSequence rotation;
  int terms = 256;
  SequenceMode mode = SequenceMode::kPerBand;
  float exposure_stops = 0;
  // Frames go to out_dir/frame_NNNN<frame_extension> (.png, .exr or .ply);
  // empty out_dir: compute errors only.
  std::filesystem::path out_dir;
  std::string frame_extension = ".png";
};

// Every sequence's frame i in `dir`: frame_0007.png, ... (the same names for
// rotations, material edits and moving area lights).
std::filesystem::path SequenceFramePath(const std::filesystem::path& dir, int index,
                                        std::string_view extension);

// dir/errors.csv of a sequence: "frame,<column>,rel_rms,seconds" and a line
// a frame, the frame's `parameter` (degrees, a BRDF) in the second column.
template <typename Frame, typename Parameter>
absl::Status WriteErrorsCsv(const std::filesystem::path& dir, const char* column,
                            std::span<const Frame> frames, Parameter Frame::*parameter) {
  std::string csv = absl::StrCat("frame,", column, ",rel_rms,seconds\n");
  for (const Frame& f : frames)
    absl::StrAppend(&csv, f.index, ",", f.*parameter, ",", f.rel_rms, ",", f.seconds, "\n");
  return AtomicWriteText(dir / "errors.csv", csv);
}

// Over a sequence's frames: what `relight` prints and the charts plot.
struct SequenceSummary {
  double mean_rel_rms = 0, max_rel_rms = 0;
  double mean_seconds = 0;
};
SequenceSummary Summarize(std::span<const SequenceFrame> frames);

// Also writes out_dir/errors.csv (frame, degrees, rel_rms, seconds).
absl::StatusOr<std::vector<SequenceFrame>> RelightSequence(const std::filesystem::path& store,
                                                           std::string_view env_spec,
                                                           const SequenceOptions& options);

}  // namespace wavebake::driver
