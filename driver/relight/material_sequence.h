#pragma once
// `wavebake relight STORE --brdf-sequence KIND:FROM:TO:FRAMES[:HOLD]`:
// material editing on a visibility store (Overbeck,
// overbeck-temporal-coherence.md ch. 4, "Basic incremental for BRDF
// editing"). The BRDF's parameter moves from FROM to TO over FRAMES frames
// (geometrically for the phong and blinn exponents, linearly for the ggx
// roughness), then stays at TO for HOLD more frames; the lighting and view
// stay. Every frame relights through the triple product
// (runtime/glossy/glossy_relighter.h) with a budget of `brdf_terms` BRDF
// coefficients per sample:
//
//   none   each sample's slice cut to its brdf_terms largest coefficients
//          (the non-incremental approximation);
//   basic  Eq. 4.2–4.5 per sample: Δρ = the brdf_terms largest entries of
//          ρ_new − ρ̃, B += ⟨V, P(L·Δρ)⟩ (the product is linear in ρ),
//          ρ̃ += Δρ. Held static, ρ̃ reaches ρ_new term by term: after
//          ⌈nonzeros / brdf_terms⌉ frames the image is the exact one.
//
// Each frame's error is against that frame relit with every BRDF
// coefficient (the same lighting terms), so it isolates what the BRDF
// budget costs.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "runtime/glossy/glossy_store.h"

namespace wavebake::driver {

struct BrdfSequence {
  std::string kind;  // phong | blinn | ggx
  double from = 0, to = 0;
  int frames = 0, hold = 0;
  // The BRDF spec of frame i (ParseBrdf spelling).
  std::string At(int i) const;
  int total() const { return frames + hold; }
};

// "KIND:FROM:TO:FRAMES[:HOLD]"; errors name the `brdf-sequence` flag.
absl::StatusOr<BrdfSequence> ParseBrdfSequence(std::string_view spec);

enum class MaterialMode { kNonIncremental, kBasic };

struct MaterialSequenceOptions {
  BrdfSequence sequence;
  int terms = 256;  // lighting terms
  MaterialMode mode = MaterialMode::kBasic;
  GlossyOptions glossy;  // its slices.terms is the BRDF budget per sample per frame
  float exposure_stops = 0;
  std::filesystem::path out_dir;  // frames + errors.csv; empty: errors only
  std::string frame_extension = ".png";
};

struct MaterialFrame {
  int index = 0;
  std::string brdf;
  double rel_rms = 0;  // vs every BRDF coefficient, unmasked cells, RGB
  double seconds = 0;  // slices of the frame's BRDF + update + relight
};

// Also writes out_dir/errors.csv (frame, brdf, rel_rms, seconds).
absl::StatusOr<std::vector<MaterialFrame>> RelightMaterialSequence(
    const std::filesystem::path& store, std::string_view env_spec,
    const MaterialSequenceOptions& options);

}  // namespace wavebake::driver
