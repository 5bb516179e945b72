// `wavebake relight OUT.wbk --env ENV [--terms 256] [--rotate DEG] [--brdf B] --out
// IMG.(exr|png)|MESH.(ply|gltf|glb)` (DESIGN.md §5): Eq. 8 relighting of a
// store under an environment, written as an image (camera layouts), a
// vertex-coloured mesh (mesh layouts) or a lightmap and a glTF carrying it
// (uv layouts); a visibility store through the triple product with --brdf
// (runtime/glossy_store.h), --brdf-sequence editing its material
// (driver/material_command.h). With --rotate-sequence, a rotating environment over
// many frames (runtime/relight_sequence.h): frames and errors.csv into --out.
// With --area-light, near-field planar lights instead (driver/area_light_commands.h).
#include <cstdio>

#include "cli/area_light_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/glossy_flags.h"
#include "driver/material_command.h"
#include "runtime/relight_sequence.h"
#include "runtime/store_relight.h"

namespace wavebake::cli {
namespace {

struct RelightFlags {
  std::string store, env, out;
  int terms = 256;
  double rotate = 0;
  float exposure = 0;
  std::string rotate_sequence, brdf_sequence, incremental, frame_format = "png";
  GlossyFlags glossy;
  driver::AreaLightCommand area;
};

// --incremental, already checked to be none, basic or per-band.
SequenceMode ModeOf(const std::string& name) {
  if (name == "none") return SequenceMode::kNonIncremental;
  return name == "basic" ? SequenceMode::kBasic : SequenceMode::kPerBand;
}

void RunSequence(const RelightFlags& f) {
  absl::StatusOr<RotateSequence> rotation = ParseRotateSequence(f.rotate_sequence);
  if (!rotation.ok()) Fail("relight", rotation.status());
  SequenceOptions options{.rotation = *rotation,
                          .terms = f.terms,
                          .mode = ModeOf(f.incremental),
                          .exposure_stops = f.exposure,
                          .out_dir = f.out,
                          .frame_extension = "." + f.frame_format};
  absl::StatusOr<std::vector<SequenceFrame>> frames = RelightSequence(f.store, f.env, options);
  if (!frames.ok()) Fail("relight", frames.status());
  const SequenceSummary sum = Summarize(*frames);
  std::printf(
      "wrote %zu frames and errors.csv to %s: rel_rms vs all lights mean %.5f max %.5f, "
      "%.2f ms/frame\n",
      frames->size(), f.out.c_str(), sum.mean_rel_rms, sum.max_rel_rms, 1e3 * sum.mean_seconds);
}

void Run(RelightFlags f) {
  if (!f.area.lights.empty() || !f.area.sequence.empty()) {
    f.area.store = f.store, f.area.out = f.out, f.area.exposure = f.exposure;
    f.area.frame_extension = "." + f.frame_format;
    absl::StatusOr<std::string> done = driver::RelightWithAreaLights(f.area);
    if (!done.ok()) Fail("relight", done.status());
    return (void)std::printf("%s\n", done->c_str());
  }
  if (f.env.empty()) Fail("relight", "--env or --area-light is required", kExitBadInput);
  if (!f.brdf_sequence.empty()) {
    if (!f.rotate_sequence.empty())
      Fail("relight", "brdf-sequence: give --rotate-sequence or --brdf-sequence, not both",
           kExitBadInput);
    driver::MaterialCommand m{f.store,
                              f.env,
                              f.out,
                              f.brdf_sequence,
                              f.incremental,
                              f.terms,
                              GlossyOf(f.glossy, "relight"),
                              f.exposure,
                              "." + f.frame_format};
    absl::StatusOr<std::string> done = driver::RelightMaterialSequence(m);
    if (!done.ok()) Fail("relight", done.status());
    return (void)std::printf("%s\n", done->c_str());
  }
  if (!f.rotate_sequence.empty()) return RunSequence(f);
  absl::Status s = RelightStoreToFile(f.store, f.env, f.terms, f.rotate, f.exposure, f.out,
                                      GlossyOf(f.glossy, "relight"));
  if (!s.ok()) Fail("relight", s);
  std::printf("wrote %s\n", f.out.c_str());
}

}  // namespace

void AddRelightCommand(CLI::App& app) {
  auto flags = std::make_shared<RelightFlags>();
  CLI::App* cmd = app.add_subcommand("relight", "relight a baked store under an environment map");
  cmd->add_option("store", flags->store, "the store (OUT.wbk) written by bake or fetch")
      ->required();
  cmd->add_option("--env", flags->env,
                  "environment: EXR or Radiance .hdr (lat-long or vertical cross), "
                  "builtin:constant or builtin:sky");
  AddAreaLightFlags(*cmd, flags->area);
  cmd->add_option("--area-light-sequence", flags->area.sequence,
                  "SEQ.json {frames, from, to}: a light moving and resizing over frames; --out is "
                  "then a directory of frames and timing.csv");
  cmd->add_flag("--distant", flags->area.distant,
                "area lights: treat them as distant (their image at the scene centre)");
  cmd->add_option("--terms", flags->terms, "wavelet lights kept (non-linear approximation)")
      ->capture_default_str();
  cmd->add_option("--rotate", flags->rotate, "rotate the environment about +Y, degrees")
      ->capture_default_str();
  cmd->add_option("--exposure", flags->exposure, "PNG/PLY exposure in stops")
      ->capture_default_str();
  AddGlossyFlags(*cmd, flags->glossy);
  cmd->add_option("--brdf-sequence", flags->brdf_sequence,
                  "KIND:FROM:TO:FRAMES[:HOLD]: material editing of a visibility store (phong/blinn "
                  "exponent, ggx roughness); --out is then a directory of frames and errors.csv");
  cmd->add_option("--rotate-sequence", flags->rotate_sequence,
                  "START:END:FRAMES: relight a rotating environment; --out is then a directory "
                  "of frames and errors.csv (error vs all wavelet lights, per frame)");
  cmd->add_option("--incremental", flags->incremental,
                  "--rotate-sequence: per-band (default, Overbeck §6.2.2), basic (ch. 4, never "
                  "resets: ghosts under fast rotation) or none; --brdf-sequence: basic (default) "
                  "or none")
      ->check(CLI::IsMember({"per-band", "basic", "none"}));
  cmd->add_option("--frame-format", flags->frame_format, "sequences: png | exr | ply")
      ->check(CLI::IsMember({"png", "exr", "ply"}))
      ->capture_default_str();
  cmd->add_option("--out", flags->out,
                  "output: .png or .exr (camera layouts), .ply (mesh layouts), .png/.exr "
                  "lightmap or .gltf/.glb mesh with it (uv layouts); a directory for "
                  "sequences")
      ->required();
  cmd->callback([flags] { Run(*flags); });
}

}  // namespace wavebake::cli
