#pragma once
// What `relight --env` does, for the command line (and anything else that
// wants the same words): one frame (Eq. 8 for a diffuse store, the triple
// product for a visibility store, runtime/glossy/glossy_store.h), a rotating
// environment over frames (driver/relight/relight_sequence.h), or material editing
// (driver/relight/material_command.h), behind one request returning the summary to
// print. Near-field lights have their own (driver/relight/area_light_commands.h).
#include <string>

#include "absl/status/statusor.h"
#include "runtime/glossy/glossy_store.h"

namespace wavebake::driver {

struct RelightCommand {
  std::string store, env, out;  // out: a file, or the directory of a sequence
  int terms = 256;              // lighting terms
  double rotate = 0;            // degrees about +Y
  float exposure = 0;           // stops, for PNG/PLY
  std::string rotate_sequence;  // START:END:FRAMES (ParseRotateSequence)
  std::string brdf_sequence;    // KIND:FROM:TO:FRAMES[:HOLD] (ParseBrdfSequence)
  std::string incremental;      // none | basic | per-band; empty: the sequence's default
  std::string frame_extension = ".png";
  GlossyOptions glossy;
};

// Errors name the flag (both sequences at once, a spelling) or come from
// the runtime (the store, the environment, the output).
absl::StatusOr<std::string> Relight(const RelightCommand& command);

}  // namespace wavebake::driver
