// `wavebake relight OUT.wbk --env ENV [--terms 256] [--rotate DEG] [--brdf B] --out
// IMG.(exr|png)|MESH.(ply|gltf|glb)` (DESIGN.md §5): Eq. 8 relighting of a
// store under an environment, written as an image (camera layouts), a
// vertex-coloured mesh (mesh layouts) or a lightmap and a glTF carrying it
// (uv layouts); a visibility store through the triple product with --brdf
// (runtime/glossy/glossy_store.h), --brdf-sequence editing its material; with
// --rotate-sequence a rotating environment over many frames, its frames and
// errors.csv into --out (driver/relight/relight_command.h). With --area-light,
// near-field planar lights instead (driver/relight/area_light_commands.h).
#include <cstdio>

#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/shading_flags.h"
#include "driver/relight/relight_command.h"

namespace wavebake::cli {
namespace {

struct RelightFlags {
  driver::RelightCommand relight;
  std::string frame_format = "png";
  GlossyFlags glossy;
  driver::AreaLightCommand area;
};

void Run(RelightFlags f) {
  driver::RelightCommand& r = f.relight;
  r.frame_extension = "." + f.frame_format;
  absl::StatusOr<std::string> done;
  if (!f.area.lights.empty() || !f.area.sequence.empty()) {
    f.area.store = r.store, f.area.out = r.out, f.area.exposure = r.exposure;
    f.area.frame_extension = r.frame_extension;
    done = driver::RelightWithAreaLights(f.area);
  } else {
    if (r.env.empty()) Fail("relight", "--env or --area-light is required", kExitBadInput);
    r.glossy = GlossyOf(f.glossy, "relight");
    done = driver::Relight(r);
  }
  if (!done.ok()) Fail("relight", done.status());
  std::printf("%s\n", done->c_str());
}

}  // namespace

void AddRelightCommand(CLI::App& app) {
  auto flags = std::make_shared<RelightFlags>();
  CLI::App* cmd = app.add_subcommand("relight", "relight a baked store under an environment map");
  cmd->add_option("store", flags->relight.store, "the store (OUT.wbk) written by bake or fetch")
      ->required();
  cmd->add_option("--env", flags->relight.env,
                  "environment: EXR or Radiance .hdr (lat-long or vertical cross), "
                  "builtin:constant or builtin:sky");
  AddAreaLightFlags(*cmd, flags->area);
  cmd->add_option("--area-light-sequence", flags->area.sequence,
                  "SEQ.json {frames, from, to}: a light moving and resizing over frames; --out is "
                  "then a directory of frames and timing.csv");
  cmd->add_flag("--distant", flags->area.distant,
                "area lights: treat them as distant (their image at the scene centre)");
  cmd->add_option("--terms", flags->relight.terms, "wavelet lights kept (non-linear approximation)")
      ->capture_default_str();
  cmd->add_option("--rotate", flags->relight.rotate, "rotate the environment about +Y, degrees")
      ->capture_default_str();
  cmd->add_option("--exposure", flags->relight.exposure, "PNG/PLY exposure in stops")
      ->capture_default_str();
  AddGlossyFlags(*cmd, flags->glossy);
  cmd->add_option("--brdf-sequence", flags->relight.brdf_sequence,
                  "KIND:FROM:TO:FRAMES[:HOLD]: material editing of a visibility store (phong/blinn "
                  "exponent, ggx roughness); --out is then a directory of frames and errors.csv");
  cmd->add_option("--rotate-sequence", flags->relight.rotate_sequence,
                  "START:END:FRAMES: relight a rotating environment; --out is then a directory "
                  "of frames and errors.csv (error vs all wavelet lights, per frame)");
  cmd->add_option("--incremental", flags->relight.incremental,
                  "--rotate-sequence: per-band (default, Overbeck §6.2.2), basic (ch. 4, never "
                  "resets: ghosts under fast rotation) or none; --brdf-sequence: basic (default) "
                  "or none")
      ->check(CLI::IsMember({"per-band", "basic", "none"}));
  cmd->add_option("--frame-format", flags->frame_format, "sequences: png | exr | ply")
      ->check(CLI::IsMember({"png", "exr", "ply"}))
      ->capture_default_str();
  cmd->add_option("--out", flags->relight.out,
                  "output: .png or .exr (camera layouts), .ply (mesh layouts), .png/.exr "
                  "lightmap or .gltf/.glb mesh with it (uv layouts); a directory for "
                  "sequences")
      ->required();
  cmd->callback([flags] { Run(*flags); });
}

}  // namespace wavebake::cli
