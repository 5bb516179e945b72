// `wavebake relight OUT.wbk --env ENV [--terms 256] [--rotate DEG] [--brdf B]
// --out IMG.(exr|png)|MESH.ply` (DESIGN.md §5): a store relit under an
// environment (Eq. 8 for diffuse stores, the triple product with a BRDF for
// visibility stores), written as an image (camera layouts), a
// vertex-coloured mesh (mesh layouts) or a lightmap and a glTF carrying it
// (uv layouts). With --area-light, near-field planar lights instead
// (driver/area_light_commands.h). The sequence modes are in
// cli/cmd_relight_sequences.cc.
#include <cstdio>

#include "cli/area_light_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/relight_flags.h"

namespace wavebake::cli {
namespace {

void Run(RelightFlags f) {
  if (!f.area.lights.empty() || !f.area.sequence.empty()) {
    f.area.store = f.store, f.area.out = f.out, f.area.exposure = f.exposure;
    f.area.frame_extension = "." + f.frame_format;
    absl::StatusOr<std::string> done = driver::RelightWithAreaLights(f.area);
    if (!done.ok()) Fail("relight", done.status());
    return (void)std::printf("%s\n", done->c_str());
  }
  if (f.env.empty()) Fail("relight", "--env or --area-light is required", kExitBadInput);
  if (!f.brdf_sequence.empty()) return RunBrdfSequence(f);
  if (!f.rotate_sequence.empty()) return RunRotateSequence(f);
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
  cmd->add_option("--rotate-sequence", flags->rotate_sequence,
                  "START:END:FRAMES: relight a rotating environment; --out is then a directory "
                  "of frames and errors.csv (error vs all wavelet lights, per frame)");
  cmd->add_option("--brdf-sequence", flags->brdf_sequence,
                  "KIND:FROM:TO:FRAMES[:HOLD]: material editing on a visibility store, the "
                  "phong/blinn exponent or ggx roughness from FROM to TO, then HOLD frames at "
                  "TO; --out is a directory of frames and errors.csv (error vs every BRDF term)");
  cmd->add_option("--incremental", flags->incremental,
                  "rotations: per-band (default, Overbeck §6.2.2), basic (ch. 4, never resets: "
                  "ghosts under fast rotation) or none; materials: basic (default, --brdf-terms "
                  "per sample per frame, converges when held) or none")
      ->check(CLI::IsMember({"per-band", "basic", "none"}));
  cmd->add_option("--frame-format", flags->frame_format, "sequences: png | exr | ply")
      ->check(CLI::IsMember({"png", "exr", "ply"}))
      ->capture_default_str();
  cmd->add_option("--out", flags->out,
                  "output: .png or .exr (camera layouts), .ply (mesh layouts), .png/.exr "
                  "lightmap or .gltf/.glb mesh with it (uv layouts); a directory for the "
                  "sequences")
      ->required();
  cmd->callback([flags] { Run(*flags); });
}

}  // namespace wavebake::cli
