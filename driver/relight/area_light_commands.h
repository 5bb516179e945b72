#pragma once
// What `relight --area-light` and `eval --reference --area-light` do, for the
// command line (and anything else that wants the same words): the near-field
// path of driver/relight/area_relight.h and runtime/reference/area_eval.h behind one request,
// returning the text to print.
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace wavebake::driver {

struct AreaLightCommand {
  std::string store;
  std::vector<std::string> lights;  // LIGHT.json files (their lights add)
  std::string sequence;             // SEQ.json: relight a moving light (--out is a directory)
  double source_fraction = 0.01, target_fraction = 0.30;
  bool table = false;  // memory-based coupling coefficients instead of computed ones
  bool distant = false;
  float exposure = 0;
  std::string out, frame_extension = ".png";
  std::string reference_out;  // eval: also write the reference image (.png, .exr or .ply)
  int threads = 0;
};

// One frame to `out`, or the sequence's frames into it; returns a summary line.
absl::StatusOr<std::string> RelightWithAreaLights(const AreaLightCommand& command);

// The error against the Monte-Carlo reference (and of the distant treatment,
// and the grazing loss); json: one JSON object, else a few lines.
absl::StatusOr<std::string> EvaluateWithAreaLights(const AreaLightCommand& command,
                                                   int reference_batches, bool json);

}  // namespace wavebake::driver
