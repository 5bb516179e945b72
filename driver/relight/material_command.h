#pragma once
// What `relight --brdf-sequence` does, for the command line (and anything
// else that wants the same words): material editing of a visibility store
// (driver/relight/material_sequence.h, Overbeck ch. 4) behind one request,
// returning the summary to print.
#include <string>

#include "absl/status/statusor.h"
#include "runtime/glossy/glossy_store.h"

namespace wavebake::driver {

struct MaterialCommand {
  std::string store, env, out;  // out: the directory of frames and errors.csv
  std::string sequence;         // KIND:FROM:TO:FRAMES[:HOLD] (ParseBrdfSequence)
  std::string incremental;      // basic (default when empty) | none
  int terms = 256;              // lighting terms
  GlossyOptions glossy;         // its slices.terms: BRDF terms per sample per frame
  float exposure = 0;
  std::string frame_extension = ".png";
};

// Errors: the sequence or incremental spelling (naming the flag), and
// everything RelightMaterialSequence reports.
absl::StatusOr<std::string> RelightMaterialSequence(const MaterialCommand& command);

}  // namespace wavebake::driver
