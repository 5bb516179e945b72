// `wavebake relight OUT.wbk --env ENV [--terms 256] [--rotate DEG] [--brdf B]
// --out IMG.(exr|png)|MESH.ply` (DESIGN.md §5): a store relit under an
// environment (Eq. 8 for diffuse stores, the triple product with a BRDF for
// visibility stores), written as an image (camera layouts), a
// vertex-coloured mesh (mesh layouts) or a lightmap and a glTF carrying it
// (uv layouts). The sequence modes are in cli/cmd_relight_sequences.cc.
#include <cstdio>

#include "cli/command_error.h"
#include "cli/relight_flags.h"
#include "cli/commands.h"

namespace wavebake::cli {
namespace {

void Run(const RelightFlags& f) {
  if (!f.brdf_sequence.empty()) return RunBrdfSequence(f);
  if (!f.rotate_sequence.empty()) return RunRotateSequence(f);
  absl::Status s =
      RelightStoreToFile(f.store, f.env, f.terms, f.rotate, f.exposure, f.out, GlossyOf(f));
  if (!s.ok()) Fail("relight", s);
  std::printf("wrote %s\n", f.out.c_str());
}

}  // namespace

GlossyOptions GlossyOf(const RelightFlags& f) {
  GlossyOptions g{.brdf = f.brdf};
  g.slices.terms = f.brdf_terms;
  if (!f.view.empty()) {
    absl::StatusOr<Vec3> eye = ParseView(f.view);
    if (!eye.ok()) Fail("relight", eye.status());
    g.eye = *eye;
  }
  return g;
}

void AddRelightCommand(CLI::App& app) {
  auto flags = std::make_shared<RelightFlags>();
  CLI::App* cmd = app.add_subcommand("relight", "relight a baked store under an environment map");
  cmd->add_option("store", flags->store, "the store (OUT.wbk) written by bake or fetch")
      ->required();
  cmd->add_option("--env", flags->env,
                  "environment: EXR or Radiance .hdr (lat-long or vertical cross), "
                  "builtin:constant or builtin:sky")
      ->required();
  cmd->add_option("--terms", flags->terms, "wavelet lights kept (non-linear approximation)")
      ->capture_default_str();
  cmd->add_option("--rotate", flags->rotate, "rotate the environment about +Y, degrees")
      ->capture_default_str();
  cmd->add_option("--exposure", flags->exposure, "PNG/PLY exposure in stops")
      ->capture_default_str();
  cmd->add_option("--brdf", flags->brdf,
                  "material (visibility stores; a diffuse store is lambert): lambert | phong:EXP "
                  "| blinn:EXP | ggx:ROUGHNESS")
      ->capture_default_str();
  cmd->add_option("--brdf-terms", flags->brdf_terms,
                  "Haar coefficients kept per sample's BRDF slice (0: all)")
      ->capture_default_str();
  cmd->add_option("--view", flags->view,
                  "X,Y,Z eye position for glossy BRDFs on mesh layouts (camera layouts use the "
                  "baked camera)");
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
