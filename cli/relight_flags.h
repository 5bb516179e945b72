#pragma once
// The flags of `wavebake relight` (cli/cmd_relight.cc), shared with its
// sequence modes (cli/cmd_relight_sequences.cc).
#include <string>

#include "cli/glossy_flags.h"
#include "driver/area_light_commands.h"

namespace wavebake::cli {

struct RelightFlags {
  std::string store, env, out;
  int terms = 256;
  double rotate = 0;
  float exposure = 0;
  std::string rotate_sequence, brdf_sequence, frame_format = "png";
  std::string incremental;  // empty: the sequence's default (per-band; basic for materials)
  GlossyFlags glossy;
  driver::AreaLightCommand area;
};

// --rotate-sequence and --brdf-sequence: frames and errors.csv into --out.
void RunRotateSequence(const RelightFlags& f);
void RunBrdfSequence(const RelightFlags& f);

}  // namespace wavebake::cli
