// `wavebake relight OUT.wbk --env ENV [--terms 256] [--rotate DEG] --out
// IMG.(exr|png)|MESH.ply` (DESIGN.md §5): Eq. 8 relighting of a store under
// an environment, written as an image (camera layouts) or a vertex-coloured
// mesh (mesh layouts).
#include <cstdio>

#include "cli/command_error.h"
#include "cli/runtime_commands.h"
#include "runtime/store_relight.h"

namespace wavebake::cli {
namespace {

struct RelightFlags {
  std::string store, env, out;
  int terms = 256;
  double rotate = 0;
  float exposure = 0;
};

void Run(const RelightFlags& f) {
  absl::Status s = RelightToFile(f.store, f.env, f.terms, f.rotate, f.exposure, f.out);
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
                  "builtin:constant or builtin:sky")
      ->required();
  cmd->add_option("--terms", flags->terms, "wavelet lights kept (non-linear approximation)")
      ->capture_default_str();
  cmd->add_option("--rotate", flags->rotate, "rotate the environment about +Y, degrees")
      ->capture_default_str();
  cmd->add_option("--exposure", flags->exposure, "PNG/PLY exposure in stops")
      ->capture_default_str();
  cmd->add_option("--out", flags->out, "output: .png or .exr (camera layouts), .ply (mesh layouts)")
      ->required();
  cmd->callback([flags] { Run(*flags); });
}

}  // namespace wavebake::cli
